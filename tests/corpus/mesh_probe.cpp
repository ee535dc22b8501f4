// One file of the mesh corpus, in a process of its own so that a crash, a hang or a runaway
// allocation is seen by the driver (mesh_corpus_test.cpp) as what it is. Loads the file, scales
// the mesh to a largest extent of kFitMetres about its bounds' centre (corpus models come in any
// unit) and samples it at d = 2 cm. Exit 0: it became a body shape (the particle count printed);
// kExitNamedError: a sandphys::Error whose message names the file; anything else is a failure.
#include <sandphys/sandphys.h>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <string>

#include "corpus/corpus_exit.h"

int main(int argc, char** argv) {
  using namespace sandphys;
  if (argc != 2) {
    std::fprintf(stderr, "usage: mesh_probe FILE\n");
    return corpus::kExitUsage;
  }
  const std::string file = argv[1];
  try {
    TriangleMesh mesh = loadMesh(file);
    Vec3 lo = mesh.vertices.front(), hi = lo;
    for (const Vec3& v : mesh.vertices) {
      lo = {std::min(lo.x, v.x), std::min(lo.y, v.y), std::min(lo.z, v.z)};
      hi = {std::max(hi.x, v.x), std::max(hi.y, v.y), std::max(hi.z, v.z)};
    }
    const double extent = std::max({double(hi.x) - lo.x, double(hi.y) - lo.y, double(hi.z) - lo.z});
    const double scale = extent > 0.0 ? corpus::kFitMetres / extent : 1.0;
    for (Vec3& v : mesh.vertices) {
      v = {float((v.x - 0.5 * (double(lo.x) + hi.x)) * scale),
           float((v.y - 0.5 * (double(lo.y) + hi.y)) * scale),
           float((v.z - 0.5 * (double(lo.z) + hi.z)) * scale)};
    }
    const SampledMesh sampled = sampleMesh(mesh, corpus::kDiameter);
    std::printf("%zu particles, %zu triangles, %s\n", sampled.centres.size(), mesh.triangles.size(),
                sampled.closed ? "closed" : "open");
    return corpus::kExitBody;
  } catch (const Error& error) {
    const std::string message = error.what();
    std::printf("%s\n", message.c_str());
    return message.find(file) != std::string::npos ? corpus::kExitNamedError
                                                   : corpus::kExitUnnamedError;
  } catch (const std::exception& error) {
    std::printf("not a sandphys::Error: %s\n", error.what());
    return corpus::kExitOtherException;
  }
}
