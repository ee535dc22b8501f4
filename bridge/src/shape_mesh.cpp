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
#include <map>
#include <string>
#include <utility>

#include "conversions.h"

namespace sandphys::bullet {

namespace {

// Unit directions at the vertices of an icosahedron subdivided `level` times: even coverage of
// the sphere, neighbours 1.107 / 2^level rad apart.
std::vector<btVector3> icosphereDirections(int level) {
  const btScalar t = btScalar((1.0 + std::sqrt(5.0)) / 2.0);
  std::vector<btVector3> points = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                                   {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                                   {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  std::vector<std::array<int, 3>> faces = {
      {0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
      {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
      {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (btVector3& p : points) p.normalize();
  for (int l = 0; l < level; ++l) {
    std::map<std::pair<int, int>, int> midpoints;
    auto midpoint = [&](int a, int b) {
      const std::pair<int, int> key = std::minmax(a, b);
      const auto found = midpoints.find(key);
      if (found != midpoints.end()) return found->second;
      points.push_back((points[std::size_t(a)] + points[std::size_t(b)]).normalized());
      const int index = int(points.size()) - 1;
      midpoints.emplace(key, index);
      return index;
    };
    std::vector<std::array<int, 3>> finer;
    finer.reserve(faces.size() * 4);
    for (const auto& f : faces) {
      const int ab = midpoint(f[0], f[1]);
      const int bc = midpoint(f[1], f[2]);
      const int ca = midpoint(f[2], f[0]);
      finer.push_back({f[0], ab, ca});
      finer.push_back({f[1], bc, ab});
      finer.push_back({f[2], ca, bc});
      finer.push_back({ab, bc, ca});
    }
    faces = std::move(finer);
  }
  return points;
}

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
  for (const btVector3& direction : icosphereDirections(levelFor(radius, maxChordError))) {
    const btVector3 p = shape.localGetSupportingVertex(direction);
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
