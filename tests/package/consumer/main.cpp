// An outside program that uses the installed sandphys: a few granules above a floor, stepped
// like a game would, must fall as gravity says, and a mesh file must load into a body. Exits
// non-zero otherwise.
#include <sandphys/sandphys.h>

#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <vector>

namespace {

// Height (m) of every granule, in body order.
std::vector<double> granuleHeights(const sandphys::World& world) {
  std::vector<double> heights;
  for (const sandphys::BodyState& body : world.readBodies()) {
    if (body.granule && body.alive) heights.push_back(body.position.y);
  }
  return heights;
}

}  // namespace

int main() {
  try {
    sandphys::GpuContext gpu = sandphys::GpuContext::headless();
    std::printf("device: %s\n", gpu.description().c_str());
    std::fflush(stdout);  // keep it before any failure message when both go to one pipe

    sandphys::World world(gpu, sandphys::WorldSettings{.maxBodies = 64});
    world.addCollider(sandphys::Plane{});  // the floor, y = 0
    // 8 granules 10 cm up, 4 cm apart: they fall freely during the few milliseconds below.
    const sandphys::BodyRange granules = world.addGranules(sandphys::GranuleBlock{
        .center = {0.0f, 0.1f, 0.0f}, .countX = 2, .countY = 2, .countZ = 2});

    const std::vector<double> before = granuleHeights(world);
    for (int frame = 0; frame < 6; ++frame) world.step(1.0f / 600.0f);
    const std::vector<double> after = granuleHeights(world);

    // Free fall from rest: drop = g t^2 / 2 (semi-implicit Euler adds a factor 1 + 1/substeps).
    // Loose bounds on purpose: this test is about packaging; tests/physics checks the numbers.
    const double t = world.simulatedTime();
    const double expected = 0.5 * 9.81 * t * t;
    if (granules.size() != 8 || before.size() != 8 || after.size() != 8 || t <= 0.0) {
      std::fprintf(stderr,
                   "FAIL: expected 8 granules and some simulated time, got %u/%zu/%zu, %g s\n",
                   granules.size(), before.size(), after.size(), t);
      return 1;
    }
    for (std::size_t i = 0; i < after.size(); ++i) {
      const double drop = before[i] - after[i];
      if (!std::isfinite(drop) || drop < 0.5 * expected || drop > 2.0 * expected) {
        std::fprintf(stderr, "FAIL: granule %zu fell %g m in %g s; free fall gives %g m\n", i, drop,
                     t, expected);
        return 1;
      }
    }
    std::printf("ok: 8 granules fell %.3g m in %.3g s (%llu substeps), free fall gives %.3g m\n",
                before[0] - after[0], t, static_cast<unsigned long long>(world.stepCount()),
                expected);

    // A body from a mesh file: the package must bring assimp into the link and the run.
    const std::filesystem::path obj =
        std::filesystem::temp_directory_path() / "sandphys_consumer_tetrahedron.obj";
    std::ofstream(obj) << "v 0 0 0\nv 0.05 0 0\nv 0 0.05 0\nv 0 0 0.05\n"
                          "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    const sandphys::SampledMesh rock =
        sandphys::sampleMesh(sandphys::loadMesh(obj), world.settings().particleDiameter);
    std::filesystem::remove(obj);
    const double volume = 0.05 * 0.05 * 0.05 / 6.0;
    if (!rock.closed || std::abs(rock.volume - volume) > 1e-9) {
      std::fprintf(stderr, "FAIL: the tetrahedron file gave volume %g m^3 (closed %d), not %g\n",
                   rock.volume, int(rock.closed), volume);
      return 1;
    }
    world.addBody(rock.shape, {.position = {0.0f, 0.3f, 0.0f}});
    std::printf("ok: a tetrahedron from an OBJ file became a body of %zu particles\n",
                rock.centres.size());
    return 0;
  } catch (const sandphys::Error& error) {
    std::fprintf(stderr, "FAIL: sandphys::Error: %s\n", error.what());
    return 1;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "FAIL: %s\n", error.what());
    return 1;
  }
}
