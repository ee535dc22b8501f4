#include "sandphys/bullet/shape_mesh.h"

#include <BulletCollision/CollisionShapes/btCompoundShape.h>
#include <BulletCollision/CollisionShapes/btConcaveShape.h>
#include <BulletCollision/CollisionShapes/btConvexShape.h>
#include <BulletCollision/CollisionShapes/btTriangleCallback.h>
#include <LinearMath/btConvexHullComputer.h>
#include <LinearMath/btTransform.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>

#include "sandphys/bullet/conversions.h"

namespace sandphys::bullet {

namespace {

// Subdivision level whose facets on a sphere of `radius` sag at most `maxChordError`.
int levelFor(btScalar radius, float maxChordError) {
  // Sag of a chord spanning angle θ on radius R: R (1 - cos θ/2) ≈ R θ² / 8.
  const double theta = std::sqrt(8.0 * double(maxChordError) / std::max(double(radius), 1e-9));
  const double level = std::ceil(std::log2(1.1071487 / std::max(theta, 1e-6)));
  return int(std::clamp(level, 1.0, 6.0));
}

void appendTransformed(TriangleMesh& into, const TriangleMesh& part, const btTransform& transform) {
  const auto base = std::uint32_t(into.vertices.size());
  for (const Vec3& v : part.vertices) into.vertices.push_back(toSand(transform(toBullet(v))));
  for (const auto& t : part.triangles) {
    into.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  }
}

TriangleMesh convexMesh(const btConvexShape& shape, float maxChordError) {
  btVector3 centre;
  btScalar radius = 0;
  shape.getBoundingSphere(centre, radius);
  std::vector<btScalar> coords;
  // Directions spread evenly over the sphere: the vertices of a unit icosphere.
  for (const Vec3& direction : icosphereMesh(1.0, levelFor(radius, maxChordError)).vertices) {
    const btVector3 p = shape.localGetSupportingVertex(toBullet(direction));
    coords.insert(coords.end(), {p.x(), p.y(), p.z()});
  }
  btConvexHullComputer hull;
  hull.compute(coords.data(), int(3 * sizeof(btScalar)), int(coords.size() / 3), 0, 0);
  TriangleMesh mesh;
  btVector3 inside(0, 0, 0);
  const auto pointCount = coords.size() / 3;
  for (int i = 0; i < hull.vertices.size(); ++i) {
    // The hull computer works on quantised coordinates (a few 1e-5 off): each of its vertices is
    // one of the support points, so take that point's exact position.
    const btVector3& v = hull.vertices[i];
    std::size_t nearest = 0;
    btScalar best = BT_LARGE_FLOAT;
    for (std::size_t k = 0; k < pointCount; ++k) {
      const btVector3 p(coords[3 * k], coords[3 * k + 1], coords[3 * k + 2]);
      const btScalar d2 = (p - v).length2();
      if (d2 < best) {
        best = d2;
        nearest = k;
      }
    }
    const btVector3 exact(coords[3 * nearest], coords[3 * nearest + 1], coords[3 * nearest + 2]);
    mesh.vertices.push_back(toSand(exact));
    inside += exact;
  }
  if (hull.vertices.size() > 0) inside /= btScalar(hull.vertices.size());
  for (int f = 0; f < hull.faces.size(); ++f) {
    // Each face is a convex polygon of hull edges: a fan from its first corner.
    const btConvexHullComputer::Edge* first = &hull.edges[hull.faces[f]];
    std::vector<int> corners;
    const btConvexHullComputer::Edge* edge = first;
    do {
      corners.push_back(edge->getSourceVertex());
      edge = edge->getNextEdgeOfFace();
    } while (edge != first);
    for (std::size_t k = 1; k + 1 < corners.size(); ++k) {
      std::array<std::uint32_t, 3> tri = {std::uint32_t(corners[0]), std::uint32_t(corners[k]),
                                          std::uint32_t(corners[k + 1])};
      const btVector3 a = toBullet(mesh.vertices[std::size_t(corners[0])]);
      const btVector3 b = toBullet(mesh.vertices[std::size_t(corners[k])]);
      const btVector3 c = toBullet(mesh.vertices[std::size_t(corners[k + 1])]);
      // Wound outward: the normal points away from a point inside the convex solid.
      if ((b - a).cross(c - a).dot(a - inside) < 0) std::swap(tri[1], tri[2]);
      mesh.triangles.push_back(tri);
    }
  }
  return mesh;
}

class Collect : public btTriangleCallback {
 public:
  explicit Collect(TriangleMesh& mesh) : m_mesh(mesh) {}
  void processTriangle(btVector3* triangle, int, int) override {
    const auto base = std::uint32_t(m_mesh.vertices.size());
    for (int i = 0; i < 3; ++i) m_mesh.vertices.push_back(toSand(triangle[i]));
    m_mesh.triangles.push_back({base, base + 1, base + 2});
  }

 private:
  TriangleMesh& m_mesh;
};

TriangleMesh meshOf(const btCollisionShape& shape, float maxChordError) {
  if (shape.isCompound()) {
    const auto& compound = static_cast<const btCompoundShape&>(shape);
    TriangleMesh mesh;
    for (int i = 0; i < compound.getNumChildShapes(); ++i) {
      appendTransformed(mesh, meshOf(*compound.getChildShape(i), maxChordError),
                        compound.getChildTransform(i));
    }
    return mesh;
  }
  if (shape.isConvex()) return convexMesh(static_cast<const btConvexShape&>(shape), maxChordError);
  if (shape.isConcave() && shape.getShapeType() != STATIC_PLANE_PROXYTYPE) {
    TriangleMesh mesh;
    Collect collect(mesh);
    const btScalar huge = btScalar(1e30);
    static_cast<const btConcaveShape&>(shape).processAllTriangles(
        &collect, btVector3(-huge, -huge, -huge), btVector3(huge, huge, huge));
    return mesh;
  }
  throw MeshError(std::string("Bullet shape '") + shape.getName() +
                  "': sandphys cannot sample its surface (only convex, compound and triangle-mesh "
                  "shapes; for an infinite plane add a sandphys Plane collider)");
}

}  // namespace

TriangleMesh shapeMesh(const btCollisionShape& shape, float maxChordError) {
  if (!(maxChordError > 0.0f)) {
    throw InvalidArgument("maxChordError " + std::to_string(maxChordError) + ": must be > 0 m");
  }
  TriangleMesh mesh = meshOf(shape, maxChordError);
  mesh.source = std::string("Bullet shape '") + shape.getName() + "'";
  validateMesh(mesh);
  return mesh;
}

}  // namespace sandphys::bullet
