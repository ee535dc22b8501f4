#include "render/collider_mesh.h"

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <variant>

namespace sandphys::render {

namespace {

// Segments around a wall of revolution: smooth enough at the sizes a sample shows.
constexpr int kSegments = 96;
// MeshVertex::cutaway of a plane: seen only from its free side.
constexpr float kOneSided = 2.0f;

struct MeshBuilder {
  std::vector<MeshVertex>& out;
  float cutaway = 0.0f;

  void vertex(const Eigen::Vector3f& p, const Eigen::Vector3f& n) {
    out.push_back({p.x(), p.y(), p.z(), cutaway, n.x(), n.y(), n.z(), 0.0f});
  }
  // A quad a-b-c-d with one normal per corner.
  void quad(const Eigen::Vector3f (&p)[4], const Eigen::Vector3f (&n)[4]) {
    for (int i : {0, 1, 2, 0, 2, 3}) vertex(p[i], n[i]);
  }

  // A plane is infinite: it is drawn as its cut through the scene's box (`clipLo`, `clipHi`), the
  // part the scene can show, so that a floor or wall seen edge-on does not fill the picture.
  void operator()(const Plane& plane) {
    Eigen::Vector3f n(plane.normal.x, plane.normal.y, plane.normal.z);
    const float length = n.norm();
    if (!(length > 0.0f)) return;
    n /= length;
    const float offset = plane.offset / length;
    const Eigen::Vector3f middle = 0.5f * (clipLo + clipHi);
    const Eigen::Vector3f centre = middle - (n.dot(middle) - offset) * n;
    Eigen::Vector3f u =
        n.cross(std::abs(n.y()) < 0.9f ? Eigen::Vector3f::UnitY() : Eigen::Vector3f::UnitX());
    u = u.normalized() * (clipHi - clipLo).norm();
    const Eigen::Vector3f v = n.cross(u);
    std::vector<Eigen::Vector3f> polygon{centre - u - v, centre + u - v, centre + u + v,
                                         centre - u + v};
    // Sutherland-Hodgman against the box's six faces.
    for (int axis = 0; axis < 3; ++axis) {
      for (const float side : {-1.0f, 1.0f}) {
        const float limit = side < 0.0f ? clipLo[axis] : clipHi[axis];
        auto inside = [&](const Eigen::Vector3f& p) { return side * (p[axis] - limit) <= 0.0f; };
        std::vector<Eigen::Vector3f> kept;
        for (std::size_t i = 0; i < polygon.size(); ++i) {
          const Eigen::Vector3f& a = polygon[i];
          const Eigen::Vector3f& b = polygon[(i + 1) % polygon.size()];
          if (inside(a)) kept.push_back(a);
          if (inside(a) != inside(b)) {
            kept.push_back(a + (b - a) * ((limit - a[axis]) / (b[axis] - a[axis])));
          }
        }
        polygon = std::move(kept);
        if (polygon.size() < 3) return;  // the plane misses the box
      }
    }
    // The normal points into the free half-space, where the sand and usually the eye are.
    cutaway = kOneSided;
    for (std::size_t i = 1; i + 1 < polygon.size(); ++i) {
      for (const Eigen::Vector3f& p : {polygon[0], polygon[i], polygon[i + 1]}) vertex(p, n);
    }
    cutaway = 0.0f;
  }

  void operator()(const Box& box) {
    const Eigen::Quaternionf q(box.orientation.w, box.orientation.x, box.orientation.y,
                               box.orientation.z);
    const Eigen::Matrix3f r = q.normalized().toRotationMatrix();
    const Eigen::Vector3f c(box.center.x, box.center.y, box.center.z);
    const Eigen::Vector3f h(box.halfExtents.x, box.halfExtents.y, box.halfExtents.z);
    cutaway = box.inside ? 1.0f : 0.0f;
    for (int axis = 0; axis < 3; ++axis) {
      for (float sign : {-1.0f, 1.0f}) {
        const int a = (axis + 1) % 3;
        const int b = (axis + 2) % 3;
        Eigen::Vector3f local[4];
        const float corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
        for (int i = 0; i < 4; ++i) {
          local[i] = Eigen::Vector3f::Zero();
          local[i][axis] = sign * h[axis];
          local[i][a] = corners[i][0] * h[a];
          local[i][b] = corners[i][1] * h[b];
        }
        Eigen::Vector3f normal = Eigen::Vector3f::Zero();
        normal[axis] = sign;
        normal = r * normal;
        quad({c + r * local[0], c + r * local[1], c + r * local[2], c + r * local[3]},
             {normal, normal, normal, normal});
      }
    }
    cutaway = 0.0f;
  }

  // A wall of revolution about the vertical through `base`: radius r0 at base.y, r1 at
  // base.y + height; the outward normal leans down as the wall widens upward.
  void revolution(const Vec3& base, float r0, float r1, float height) {
    cutaway = 1.0f;
    const float slope = (r1 - r0) / height;
    for (int i = 0; i < kSegments; ++i) {
      const float a0 = 2.0f * std::numbers::pi_v<float> * float(i) / kSegments;
      const float a1 = 2.0f * std::numbers::pi_v<float> * float(i + 1) / kSegments;
      auto point = [&](float angle, float radius, float y) {
        return Eigen::Vector3f(base.x + radius * std::cos(angle), y,
                               base.z + radius * std::sin(angle));
      };
      auto normal = [&](float angle) {
        return Eigen::Vector3f(std::cos(angle), -slope, std::sin(angle)).normalized();
      };
      const float y0 = base.y;
      const float y1 = base.y + height;
      quad({point(a0, r0, y0), point(a1, r0, y0), point(a1, r1, y1), point(a0, r1, y1)},
           {normal(a0), normal(a1), normal(a1), normal(a0)});
    }
    cutaway = 0.0f;
  }

  void operator()(const Cylinder& c) { revolution(c.base, c.radius, c.radius, c.height); }

  void operator()(const Funnel& f) {
    revolution(f.outletCenter, f.outletRadius, f.outletRadius + f.height * std::tan(f.halfAngle),
               f.height);
  }

  Eigen::Vector3f clipLo;
  Eigen::Vector3f clipHi;
};

}  // namespace

std::vector<MeshVertex> buildColliderMesh(const std::vector<ColliderShape>& colliders,
                                          const Eigen::Vector3f& clipLo,
                                          const Eigen::Vector3f& clipHi) {
  std::vector<MeshVertex> vertices;
  MeshBuilder builder{vertices};
  builder.clipLo = clipLo;
  builder.clipHi = clipHi;
  for (const ColliderShape& shape : colliders) std::visit(builder, shape);
  return vertices;
}

}  // namespace sandphys::render
