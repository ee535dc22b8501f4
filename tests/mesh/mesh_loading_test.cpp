// loadMesh: files written at test time in each format, node transforms, and every bad file or
// mesh with an error that names the file and the problem.
#include <gtest/gtest.h>
#include <sandphys/sandphys.h>

#include <cmath>
#include <limits>
#include <string>

#include "mesh/mesh_files.h"
#include "mesh/mesh_shapes.h"

namespace sandphys {
namespace {

using mesh_testing::namedBox;
using mesh_testing::ScratchDirectory;

struct Bounds {
  Vec3 lo{std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity(),
          std::numeric_limits<float>::infinity()};
  Vec3 hi{-std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
          -std::numeric_limits<float>::infinity()};
};

Bounds boundsOf(const TriangleMesh& mesh) {
  Bounds b;
  for (const Vec3& v : mesh.vertices) {
    b.lo = {std::min(b.lo.x, v.x), std::min(b.lo.y, v.y), std::min(b.lo.z, v.z)};
    b.hi = {std::max(b.hi.x, v.x), std::max(b.hi.y, v.y), std::max(b.hi.z, v.z)};
  }
  return b;
}

void expectBounds(const TriangleMesh& mesh, Vec3 lo, Vec3 hi) {
  const Bounds b = boundsOf(mesh);
  EXPECT_NEAR(b.lo.x, lo.x, 1e-6) << mesh.source;
  EXPECT_NEAR(b.lo.y, lo.y, 1e-6) << mesh.source;
  EXPECT_NEAR(b.lo.z, lo.z, 1e-6) << mesh.source;
  EXPECT_NEAR(b.hi.x, hi.x, 1e-6) << mesh.source;
  EXPECT_NEAR(b.hi.y, hi.y, 1e-6) << mesh.source;
  EXPECT_NEAR(b.hi.z, hi.z, 1e-6) << mesh.source;
}

// A unit cube from any format: 8 welded corners, 12 outward triangles, volume 1.
void expectUnitCube(const TriangleMesh& mesh, const std::filesystem::path& file) {
  EXPECT_EQ(mesh.source, file.string());
  EXPECT_EQ(mesh.triangles.size(), 12u) << mesh.source;
  EXPECT_EQ(mesh.vertices.size(), 8u) << mesh.source;
  expectBounds(mesh, {0, 0, 0}, {1, 1, 1});
  const SolidProperties solid = solidProperties(mesh, 1.0);
  EXPECT_NEAR(solid.volume, 1.0, 1e-9) << mesh.source;
  EXPECT_FALSE(solid.woundInward) << mesh.source;
}

constexpr Vec3 kLo{0, 0, 0}, kHi{1, 1, 1};

TEST(LoadMesh, ObjWithQuads) {
  ScratchDirectory dir;
  const auto file = dir.write("cube.obj", mesh_testing::boxObj(kLo, kHi));
  expectUnitCube(loadMesh(file), file);
}

TEST(LoadMesh, AsciiStlWithCornersPerFacet) {
  ScratchDirectory dir;
  const auto file = dir.write("cube.stl", mesh_testing::boxStl(kLo, kHi));
  expectUnitCube(loadMesh(file), file);
}

TEST(LoadMesh, AsciiPlyWithQuads) {
  ScratchDirectory dir;
  const auto file = dir.write("cube.ply", mesh_testing::boxPly(kLo, kHi));
  expectUnitCube(loadMesh(file), file);
}

TEST(LoadMesh, GltfWithEmbeddedBuffer) {
  ScratchDirectory dir;
  const auto file = dir.write(
      "cube.gltf",
      mesh_testing::boxGltf(kLo, kHi, "[{\"primitives\": [PRIMITIVE]}]", "[{\"mesh\": 0}]", "[0]"));
  expectUnitCube(loadMesh(file), file);
}

TEST(LoadMesh, MeshesUnderNodesAreMergedWithTheirTransforms) {
  // A parent node moved up by 10 and scaled by 2 holds two meshes moved by ±3 along x (before the
  // parent's scale): world = T(0,10,0) S(2) T(±3,0,0) p, so the cubes span x in [6, 8] and
  // [-6, -4]. Composing in the wrong order would put them at [3, 5] and [-3, -1].
  ScratchDirectory dir;
  const auto file =
      dir.write("two_cubes.gltf",
                mesh_testing::boxGltf(
                    kLo, kHi, R"([{"primitives": [PRIMITIVE]}, {"primitives": [PRIMITIVE]}])",
                    R"([{"translation": [0, 10, 0], "scale": [2, 2, 2], "children": [1, 2]},
              {"mesh": 0, "translation": [3, 0, 0]}, {"mesh": 1, "translation": [-3, 0, 0]}])",
                    "[0]"));
  const TriangleMesh mesh = loadMesh(file);
  EXPECT_EQ(mesh.triangles.size(), 24u);
  EXPECT_EQ(mesh.vertices.size(), 16u);
  expectBounds(mesh, {-6, 10, 0}, {8, 12, 2});
  float xMinOfSecondHalf = std::numeric_limits<float>::infinity();
  for (std::size_t t = 12; t < 24; ++t)
    for (std::uint32_t i : mesh.triangles[t])
      xMinOfSecondHalf = std::min(xMinOfSecondHalf, mesh.vertices[i].x);
  EXPECT_NEAR(xMinOfSecondHalf, -6.0f, 1e-6);
  EXPECT_NEAR(solidProperties(mesh, 1.0).volume, 16.0, 1e-9);
}

TEST(LoadMesh, MirroringNodeKeepsTheTrianglesWoundOutward) {
  ScratchDirectory dir;
  const auto file = dir.write(
      "mirrored.gltf", mesh_testing::boxGltf(kLo, kHi, "[{\"primitives\": [PRIMITIVE]}]",
                                             R"([{"mesh": 0, "scale": [-1, 1, 1]}])", "[0]"));
  const TriangleMesh mesh = loadMesh(file);
  expectBounds(mesh, {-1, 0, 0}, {0, 1, 1});
  const SolidProperties solid = solidProperties(mesh, 1.0);
  EXPECT_NEAR(solid.volume, 1.0, 1e-9);
  EXPECT_FALSE(solid.woundInward);
}

// Runs `load`, which must throw MeshError, and checks that its message names `file` and says
// `problem`.
template <typename Load>
void expectMeshError(Load load, const std::string& file, const std::string& problem) {
  try {
    load();
    ADD_FAILURE() << "no MeshError for " << file;
  } catch (const MeshError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("'" + file + "'"), std::string::npos) << message;
    EXPECT_NE(message.find(problem), std::string::npos) << message;
  }
}

TEST(LoadMesh, MissingFile) {
  ScratchDirectory dir;
  const auto file = dir.path() / "no_such_rock.obj";
  expectMeshError([&] { loadMesh(file); }, file.string(), "does not exist");
  expectMeshError([&] { loadMesh(dir.path()); }, dir.path().string(), "not a regular file");
}

TEST(LoadMesh, AssimpFailureCarriesItsMessage) {
  ScratchDirectory dir;
  const auto garbage = dir.write("garbage.obj", "x\n");
  expectMeshError([&] { loadMesh(garbage); }, garbage.string(), "assimp could not read it: ");
  const auto unknown = dir.write("cube.unknownformat", "solid?\n");
  expectMeshError([&] { loadMesh(unknown); }, unknown.string(), "assimp could not read it: ");
  // assimp rejects an OBJ face index past the vertices itself; its reason follows ours.
  const auto outOfRange = dir.write("index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
  expectMeshError([&] { loadMesh(outOfRange); }, outOfRange.string(), "index out of range");
}

TEST(LoadMesh, FileWithoutTriangles) {
  ScratchDirectory dir;
  const auto points = dir.write("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  expectMeshError([&] { loadMesh(points); }, points.string(), "has no triangles");
  const auto lines = dir.write("lines.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\np 1 2 3\nl 1 2\n");
  expectMeshError([&] { loadMesh(lines); }, lines.string(), "has no triangles");
  const auto empty = dir.write("empty.stl", "solid nothing\nendsolid nothing\n");
  expectMeshError([&] { loadMesh(empty); }, empty.string(), "has no triangles");
}

TEST(LoadMesh, NonFiniteVertexInAFile) {
  // assimp reads "nan" and "inf" as such; the loader checks before anything can fold them away.
  ScratchDirectory dir;
  const auto nan = dir.write("nan.obj", "v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n");
  expectMeshError([&] { loadMesh(nan); }, nan.string(), "vertex 2 of mesh 0");
  expectMeshError([&] { loadMesh(nan); }, nan.string(), "(0, nan, 0) is not finite");
  const auto inf = dir.write("inf.obj", "v 0 0 0\nv inf 0 0\nv 0 1 0\nf 1 2 3\n");
  expectMeshError([&] { loadMesh(inf); }, inf.string(), "(inf, 0, 0) is not finite");
}

TEST(LoadMesh, FileWithOnlyDegenerateTriangles) {
  ScratchDirectory dir;
  const auto file = dir.write("flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 3 0 0\nf 1 2 3\nf 2 3 4\n");
  expectMeshError([&] { loadMesh(file); }, file.string(), "all 2 triangles have zero area");
}

// The same checks on a mesh built in code, by validateMesh and by everything that uses it.
TEST(ValidateMesh, HandBuiltMeshesGetTheSameChecks) {
  TriangleMesh mesh = namedBox({0, 0, 0}, {1, 1, 1}, "hand-built");
  EXPECT_NO_THROW(validateMesh(mesh));

  TriangleMesh none = mesh;
  none.triangles.clear();
  expectMeshError([&] { validateMesh(none); }, "hand-built", "has no triangles (8 vertices)");
  expectMeshError([&] { sampleMesh(none, 0.02f); }, "hand-built", "has no triangles");

  TriangleMesh nan = mesh;
  nan.vertices[5].y = std::numeric_limits<float>::quiet_NaN();
  expectMeshError([&] { validateMesh(nan); }, "hand-built", "vertex 5 = (1, nan, 1) is not finite");
  expectMeshError([&] { sampleMesh(nan, 0.02f); }, "hand-built", "vertex 5");
  expectMeshError([&] { solidProperties(nan, 1.0); }, "hand-built", "vertex 5");

  TriangleMesh inf = mesh;
  inf.vertices[2].z = -std::numeric_limits<float>::infinity();
  expectMeshError([&] { validateMesh(inf); }, "hand-built",
                  "vertex 2 = (0, 1, -inf) is not finite");

  TriangleMesh outOfRange = mesh;
  outOfRange.triangles[7][1] = 8;
  expectMeshError([&] { validateMesh(outOfRange); }, "hand-built",
                  "triangle 7 has vertex index 8, but the mesh has 8 vertices");
  expectMeshError([&] { sampleMesh(outOfRange, 0.02f); }, "hand-built", "triangle 7");
  expectMeshError([&] { analyseEdges(outOfRange); }, "hand-built", "triangle 7");

  TriangleMesh flat;
  flat.source = "hand-built";
  flat.vertices = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {0, 0, 0}};
  flat.triangles = {{0, 1, 2}, {0, 3, 1}, {1, 1, 2}};
  expectMeshError([&] { validateMesh(flat); }, "hand-built", "all 3 triangles have zero area");
  expectMeshError([&] { sampleMesh(flat, 0.02f); }, "hand-built", "zero area");
}

TEST(ValidateMesh, UnnamedMeshSaysSo) {
  TriangleMesh mesh;
  try {
    validateMesh(mesh);
    FAIL() << "an empty mesh went through";
  } catch (const MeshError& e) {
    EXPECT_NE(std::string(e.what()).find("no TriangleMesh::source"), std::string::npos) << e.what();
  }
}

TEST(LoadMesh, LoadedMeshSamplesLikeTheSameMeshBuiltInCode) {
  ScratchDirectory dir;
  const Vec3 lo{-0.1f, 0.0f, -0.05f}, hi{0.1f, 0.1f, 0.05f};
  const auto file = dir.write("box.obj", mesh_testing::boxObj(lo, hi));
  const SampledMesh loaded = sampleMesh(loadMesh(file), 0.02f);
  const SampledMesh built = sampleMesh(boxMesh(lo, hi), 0.02f);
  EXPECT_EQ(loaded.centres.size(), built.centres.size());
  EXPECT_TRUE(loaded.closed);
  EXPECT_NEAR(loaded.volume, built.volume, 1e-9);
  EXPECT_FLOAT_EQ(loaded.shape.principalInertia.x, built.shape.principalInertia.x);
}

}  // namespace
}  // namespace sandphys
