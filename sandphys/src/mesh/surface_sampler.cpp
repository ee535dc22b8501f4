#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/validation.h"
#include "mesh/mesh_checks.h"
#include "mesh/samplers.h"

namespace sandphys::mesh_detail {

void throwTooManyParticles(const std::string& source, double spacing, std::size_t maxParticles,
                           double estimate) {
  std::string need = estimate > 0.0 ? "about " + detail::formatValue(std::round(estimate))
                                    : "more than " + std::to_string(maxParticles);
  throw CapacityExceeded(
      meshName(source) + ": sampling it at spacing " + detail::formatValue(spacing) + " m needs " +
      need + " particles, but MeshSampling.maxParticles = " + std::to_string(maxParticles) +
      " (raise the limit, or sample coarser: larger spacing or diameter)");
}

namespace {

struct Corners {
  Eigen::Vector3d a;
  Eigen::Vector3d b;
  Eigen::Vector3d c;
};

// Cuts a triangle into ones no more elongated than a right isosceles triangle (longest edge at
// most twice the height over it), by halving the longest edge again and again. An equal cut of
// a long thin triangle (a board's narrow face) would otherwise follow its longest edge and put
// (length / h)² / 2 samples on an area of length × width; the pieces cost about 2 / h² per area
// like any well-shaped triangle. Triangles already that compact (every face of a cube, an
// icosphere's) are left whole, so their lattices do not change.
void splitElongated(const Corners& t, double spacing, std::vector<Corners>& out) {
  const double ab = (t.b - t.a).squaredNorm();
  const double bc = (t.c - t.b).squaredNorm();
  const double ca = (t.a - t.c).squaredNorm();
  const double longest = std::max({ab, bc, ca});
  const double twiceArea = (t.b - t.a).cross(t.c - t.a).norm();
  // longest / height = longest² / (2 · area); the margin keeps a right isosceles triangle whole.
  if (longest <= spacing * spacing || longest <= 2.0 * (1.0 + 1e-9) * twiceArea) {
    out.push_back(t);
    return;
  }
  // Rotate so that the longest edge is a-b, then cut it at its midpoint.
  const Corners r = longest == ab   ? t
                    : longest == bc ? Corners{t.b, t.c, t.a}
                                    : Corners{t.c, t.a, t.b};
  const Eigen::Vector3d middle = 0.5 * (r.a + r.b);
  splitElongated({r.a, middle, r.c}, spacing, out);
  splitElongated({middle, r.b, r.c}, spacing, out);
}

// Largest distance from a point of the triangle to its nearest corner: the circumradius of an
// acute triangle, half the longest edge otherwise.
double coveringRadius(const Corners& t) {
  const double a2 = (t.b - t.c).squaredNorm();
  const double b2 = (t.c - t.a).squaredNorm();
  const double c2 = (t.a - t.b).squaredNorm();
  const double longest2 = std::max({a2, b2, c2});
  if (2.0 * longest2 >= a2 + b2 + c2) return 0.5 * std::sqrt(longest2);  // right or obtuse
  const double twiceArea = (t.b - t.a).cross(t.c - t.a).norm();
  return std::sqrt(a2 * b2 * c2) / (2.0 * twiceArea);
}

}  // namespace

PointGrid sampleSurface(const TriangleMesh& mesh, double spacing, std::size_t maxParticles) {
  // The pieces and their cuts first, so that a hopeless request fails before any allocation. A
  // closed surface of F lattice triangles has about F/2 corners once shared ones are welded, so
  // Σ n²/2 over the pieces that are cut (n >= 2; those not cut may be thinned below) estimates
  // the count from below and never refuses a mesh that would fit.
  std::vector<Corners> pieces;
  std::vector<std::uint32_t> divisions;
  double estimate = 0.0;
  for (const auto& tri : mesh.triangles) {
    const Corners t{toEigen(mesh.vertices[tri[0]]), toEigen(mesh.vertices[tri[1]]),
                    toEigen(mesh.vertices[tri[2]])};
    // A triangle without area adds no surface; its edges belong to its neighbours as well.
    if (!hasArea(t.a, t.b, t.c)) continue;
    const std::size_t first = pieces.size();
    splitElongated(t, spacing, pieces);
    for (std::size_t p = first; p < pieces.size(); ++p) {
      const Corners& piece = pieces[p];
      const double longest =
          std::sqrt(std::max({(piece.b - piece.a).squaredNorm(), (piece.c - piece.b).squaredNorm(),
                              (piece.a - piece.c).squaredNorm()}));
      const double n = std::max(1.0, std::ceil(longest / spacing));
      if (n >= 2.0) estimate += 0.5 * n * n;
      // Capped so that the cast stays defined; such a triangle fails the estimate below anyway.
      divisions.push_back(std::uint32_t(std::min(n, 1e9)));
    }
    if (estimate > double(maxParticles)) {
      throwTooManyParticles(mesh.source, spacing, maxParticles, estimate);
    }
  }

  // Points on an edge that two triangles share come out of both, equal up to rounding; points
  // of different meshes never come closer than the spacing allows. A thousandth of the spacing
  // tells the two apart.
  const double weld = 1e-3 * spacing;
  // The rule is that every point of the surface lies within h/√3 of a sample. A piece's own
  // corners bring every point of it within its sub-triangles' covering radius c; a corner may
  // then be left out when a sample already lies within h/√3 - c of it. Lattices cut to the
  // spacing keep nearly all their corners, but a mesh finer than the spacing (triangles smaller
  // than h) gets the samples the spacing asks for, not one per vertex.
  const double reach = spacing / std::numbers::sqrt3;
  PointGrid grid(reach);
  for (std::size_t t = 0; t < pieces.size(); ++t) {
    const std::uint32_t n = divisions[t];
    const Corners& piece = pieces[t];
    const double covered = coveringRadius({piece.a, piece.a + (piece.b - piece.a) / double(n),
                                           piece.a + (piece.c - piece.a) / double(n)});
    const double thin = std::max(weld, reach - covered);
    for (std::uint32_t i = 0; i <= n; ++i) {
      for (std::uint32_t j = 0; j <= n - i; ++j) {
        const std::uint32_t k = n - i - j;
        const Eigen::Vector3d p =
            (double(i) * piece.a + double(j) * piece.b + double(k) * piece.c) / double(n);
        if (grid.addUnlessNear(p, thin) && grid.points().size() > maxParticles) {
          throwTooManyParticles(mesh.source, spacing, maxParticles, 0.0);
        }
      }
    }
  }
  return grid;
}

}  // namespace sandphys::mesh_detail
