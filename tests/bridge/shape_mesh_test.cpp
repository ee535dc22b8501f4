// Bullet collision shapes turned into closed meshes for sampling (sandphys::bullet::shapeMesh).
#include <gtest/gtest.h>

#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btBvhTriangleMeshShape.h>
#include <BulletCollision/CollisionShapes/btCapsuleShape.h>
#include <BulletCollision/CollisionShapes/btCompoundShape.h>
#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletCollision/CollisionShapes/btCylinderShape.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>
#include <BulletCollision/CollisionShapes/btStaticPlaneShape.h>
#include <BulletCollision/CollisionShapes/btTriangleMesh.h>

#include <cmath>
#include <numbers>
#include <string>

#include <sandphys/bullet/shape_mesh.h>

namespace sandphys::bullet {
namespace {

constexpr float kChord = 1e-3f;  // m

struct Bounds {
  Vec3 lo{1e9f, 1e9f, 1e9f};
  Vec3 hi{-1e9f, -1e9f, -1e9f};
};

Bounds boundsOf(const TriangleMesh& mesh) {
  Bounds b;
  for (const Vec3& v : mesh.vertices) {
    b.lo = {std::min(b.lo.x, v.x), std::min(b.lo.y, v.y), std::min(b.lo.z, v.z)};
    b.hi = {std::max(b.hi.x, v.x), std::max(b.hi.y, v.y), std::max(b.hi.z, v.z)};
  }
  return b;
}

double volumeOf(const TriangleMesh& mesh) {
  return solidProperties(mesh, 1.0).volume;
}

TEST(ShapeMesh, BoxIsItsEightCornersMarginIncluded) {
  btBoxShape box(btVector3(0.3f, 0.1f, 0.2f));
  const TriangleMesh mesh = shapeMesh(box, kChord);
  EXPECT_EQ(mesh.vertices.size(), 8u);
  EXPECT_EQ(mesh.triangles.size(), 12u);
  const Bounds b = boundsOf(mesh);
  EXPECT_FLOAT_EQ(b.hi.x, 0.3f);
  EXPECT_FLOAT_EQ(b.lo.y, -0.1f);
  EXPECT_FLOAT_EQ(b.hi.z, 0.2f);
  EXPECT_TRUE(analyseEdges(mesh).closed());
  EXPECT_NEAR(volumeOf(mesh), 0.6 * 0.2 * 0.4, 1e-6);
}

TEST(ShapeMesh, SphereFollowsItsSurfaceWithinTheChordError) {
  const float r = 0.25f;
  btSphereShape sphere(r);
  const TriangleMesh mesh = shapeMesh(sphere, kChord);
  for (const Vec3& v : mesh.vertices) {
    EXPECT_NEAR(std::hypot(v.x, v.y, v.z), r, 1e-5f);
  }
  EXPECT_TRUE(analyseEdges(mesh).closed());
  const double exact = 4.0 / 3.0 * std::numbers::pi * r * r * r;
  // An inscribed polyhedron whose facets sag at most kChord: its volume is short by at most
  // the shell of that thickness.
  EXPECT_LT(volumeOf(mesh), exact);
  EXPECT_GT(volumeOf(mesh), exact * (1.0 - 3.0 * kChord / r));
}

TEST(ShapeMesh, CapsuleAndCylinderHaveTheirBulletDimensions) {
  btCapsuleShape capsule(0.1f, 0.4f);  // radius, height of the straight part (along y)
  const Bounds c = boundsOf(shapeMesh(capsule, kChord));
  EXPECT_NEAR(c.hi.y, 0.3f, 1e-5f);
  EXPECT_NEAR(c.lo.y, -0.3f, 1e-5f);
  EXPECT_NEAR(c.hi.x, 0.1f, 2e-3f);
  btCylinderShape cylinder(btVector3(0.2f, 0.15f, 0.2f));
  const TriangleMesh mesh = shapeMesh(cylinder, kChord);
  const Bounds b = boundsOf(mesh);
  EXPECT_NEAR(b.hi.y, 0.15f, 1e-5f);
  EXPECT_NEAR(b.hi.x, 0.2f, 2e-3f);
  const double exact = std::numbers::pi * 0.2 * 0.2 * 0.3;
  EXPECT_NEAR(volumeOf(mesh), exact, 0.02 * exact);
}

TEST(ShapeMesh, ConvexHullCompoundAndTriangleMeshShapes) {
  btConvexHullShape hull;
  for (const btVector3& p :
       {btVector3(0, 0, 0), btVector3(1, 0, 0), btVector3(0, 1, 0), btVector3(0, 0, 1)}) {
    hull.addPoint(p);
  }
  hull.setMargin(0.0f);
  const TriangleMesh tetra = shapeMesh(hull, kChord);
  EXPECT_EQ(tetra.vertices.size(), 4u);
  EXPECT_NEAR(volumeOf(tetra), 1.0 / 6.0, 1e-6);

  btBoxShape box(btVector3(0.1f, 0.1f, 0.1f));
  btCompoundShape compound;
  btTransform shifted;
  shifted.setIdentity();
  shifted.setOrigin(btVector3(1.0f, 0.0f, 0.0f));
  compound.addChildShape(shifted, &box);
  const Bounds b = boundsOf(shapeMesh(compound, kChord));
  EXPECT_NEAR(b.lo.x, 0.9f, 1e-6f);
  EXPECT_NEAR(b.hi.x, 1.1f, 1e-6f);

  btTriangleMesh triangles;
  // A closed tetrahedron as four triangles.
  const btVector3 a(0, 0, 0), bx(1, 0, 0), by(0, 1, 0), bz(0, 0, 1);
  triangles.addTriangle(a, by, bx);
  triangles.addTriangle(a, bx, bz);
  triangles.addTriangle(a, bz, by);
  triangles.addTriangle(bx, by, bz);
  btBvhTriangleMeshShape shape(&triangles, true);
  const TriangleMesh fromTriangles = shapeMesh(shape, kChord);
  EXPECT_EQ(fromTriangles.triangles.size(), 4u);
  EXPECT_NEAR(volumeOf(fromTriangles), 1.0 / 6.0, 1e-6);
}

TEST(ShapeMesh, APlaneIsAClearError) {
  btStaticPlaneShape plane(btVector3(0, 1, 0), 0);
  try {
    shapeMesh(plane, kChord);
    FAIL() << "no error";
  } catch (const MeshError& error) {
    const std::string what = error.what();
    EXPECT_NE(what.find("STATICPLANE"), std::string::npos) << what;
    EXPECT_NE(what.find("Plane collider"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace sandphys::bullet
