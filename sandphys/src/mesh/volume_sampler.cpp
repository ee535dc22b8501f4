#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/validation.h"
#include "mesh/mesh_checks.h"
#include "mesh/samplers.h"

namespace sandphys::mesh_detail {
namespace {

// Where a lattice row (a ray along +x) passes through a triangle, and which way: +1 where the
// triangle faces +x (the ray leaves an outward-wound solid there), -1 where it faces -x.
struct Crossing {
  std::uint64_t row = 0;
  double x = 0.0;
  int sign = 0;
  bool operator<(const Crossing& o) const {
    if (row != o.row) return row < o.row;
    if (x != o.x) return x < o.x;
    return sign < o.sign;
  }
};

// Points in the plane of the rows, (y, z).
struct Point2 {
  double y, z;
};

bool lexLess(Point2 a, Point2 b) {
  return a.y < b.y || (a.y == b.y && a.z < b.z);
}

// Twice the signed area of (p, q, s): > 0 when s is left of p→q.
double cross(Point2 p, Point2 q, Point2 s) {
  return (q.y - p.y) * (s.z - p.z) - (q.z - p.z) * (s.y - p.y);
}

// The edge function of p→q at s, evaluated with the endpoints in a fixed order so that the two
// triangles sharing an edge get exactly opposite values, whatever the rounding.
double edgeFunction(Point2 p, Point2 q, Point2 s) {
  return lexLess(p, q) ? cross(p, q, s) : -cross(q, p, s);
}

// A tie-break for rows that pass exactly through an edge or a corner: of the two directions an
// edge has in its two (counter-clockwise) triangles, exactly one owns the points on it, so the
// ray crosses the surface once there, not twice or never (the fill rule of rasterisers).
bool ownsBoundary(Point2 from, Point2 to) {
  const double dz = to.z - from.z, dy = to.y - from.y;
  return dz < 0.0 || (dz == 0.0 && dy < 0.0);
}

}  // namespace

std::vector<Eigen::Vector3d> sampleInterior(const TriangleMesh& mesh, double spacing,
                                            const PointGrid& surface, std::size_t maxParticles) {
  const auto [lo, hi] = boundsOfTriangles(mesh);
  // A lattice centred on the bounding box: a symmetric mesh gets a symmetric filling.
  std::int64_t count[3];
  Eigen::Vector3d start;
  for (int a = 0; a < 3; ++a) {
    // Row indices must fit their integers; only parts flung far apart come near this.
    if (!((hi(a) - lo(a)) / spacing < 1e9)) {
      throwMeshError(mesh.source, "MeshSampling.fillVolume: its bounding box is " +
                                      detail::formatValue(hi(a) - lo(a)) +
                                      " m wide, more than 1e9 lattice spacings of " +
                                      detail::formatValue(spacing) + " m");
    }
    count[a] = std::int64_t(std::floor((hi(a) - lo(a)) / spacing)) + 1;
    start(a) = 0.5 * (lo(a) + hi(a)) - 0.5 * double(count[a] - 1) * spacing;
  }
  const std::int64_t ny = count[1], nz = count[2];

  std::vector<Crossing> crossings;
  for (const auto& tri : mesh.triangles) {
    Eigen::Vector3d v[3];
    Point2 p[3];
    for (int k = 0; k < 3; ++k) {
      v[k] = toEigen(mesh.vertices[tri[k]]);
      p[k] = {v[k].y(), v[k].z()};
    }
    const double area = cross(p[0], p[1], p[2]);
    // Seen edge-on from the rows: a row either misses it or runs inside its plane, where the
    // neighbouring triangles' tie-breaks decide.
    if (area == 0.0) continue;
    const int sign = area > 0.0 ? 1 : -1;
    const double zMin = std::min({p[0].z, p[1].z, p[2].z});
    const double zMax = std::max({p[0].z, p[1].z, p[2].z});
    // Rows a spacing beyond the triangle's extent in z and y are tried as well: the exact test
    // below decides, these bounds only keep the candidates few, and a row through a corner must
    // not be lost to the rounding of a division.
    const std::int64_t kFirst =
        std::max<std::int64_t>(0, std::ceil((zMin - start.z()) / spacing - 1.0));
    const std::int64_t kLast =
        std::min<std::int64_t>(nz - 1, std::floor((zMax - start.z()) / spacing + 1.0));
    for (std::int64_t k = kFirst; k <= kLast; ++k) {
      const double z = start.z() + double(k) * spacing;
      double yMin = std::numeric_limits<double>::infinity(), yMax = -yMin;
      for (int e = 0; e < 3; ++e) {
        const Point2 a = p[e], b = p[(e + 1) % 3];
        if ((a.z - z) * (b.z - z) > 0.0) continue;  // the edge is above or below the row
        const double y = a.z == b.z ? a.y : a.y + (b.y - a.y) * (z - a.z) / (b.z - a.z);
        yMin = std::min({yMin, y, a.z == b.z ? b.y : y});
        yMax = std::max({yMax, y, a.z == b.z ? b.y : y});
      }
      if (!(yMin <= yMax)) continue;
      const std::int64_t jFirst =
          std::max<std::int64_t>(0, std::ceil((yMin - start.y()) / spacing - 1.0));
      const std::int64_t jLast =
          std::min<std::int64_t>(ny - 1, std::floor((yMax - start.y()) / spacing + 1.0));
      for (std::int64_t j = jFirst; j <= jLast; ++j) {
        const Point2 s{start.y() + double(j) * spacing, z};
        // Edge functions of the edges opposite each corner, made >= 0 inside whichever way the
        // triangle turns in the plane.
        double w[3];
        bool inside = true;
        for (int e = 0; e < 3 && inside; ++e) {
          Point2 from = p[(e + 1) % 3], to = p[(e + 2) % 3];
          w[e] = double(sign) * edgeFunction(from, to, s);
          if (sign < 0) std::swap(from, to);
          inside = w[e] > 0.0 || (w[e] == 0.0 && ownsBoundary(from, to));
        }
        if (!inside) continue;
        const double x =
            (w[0] * v[0].x() + w[1] * v[1].x() + w[2] * v[2].x()) / (w[0] + w[1] + w[2]);
        crossings.push_back({std::uint64_t(k * ny + j), x, sign});
      }
    }
  }
  std::sort(crossings.begin(), crossings.end());

  std::vector<Eigen::Vector3d> interior;
  const double clearance = 0.5 * spacing;
  for (std::size_t first = 0; first < crossings.size();) {
    std::size_t last = first;
    int winding = 0;  // Σ signs of the crossings beyond the current point: its winding number
    while (last < crossings.size() && crossings[last].row == crossings[first].row) {
      winding += crossings[last].sign;
      ++last;
    }
    const std::int64_t row = std::int64_t(crossings[first].row);
    const double y = start.y() + double(row % ny) * spacing;
    const double z = start.z() + double(row / ny) * spacing;
    const std::int64_t iFirst =
        std::max<std::int64_t>(0, std::ceil((crossings[first].x - start.x()) / spacing));
    const std::int64_t iLast = std::min<std::int64_t>(
        count[0] - 1, std::floor((crossings[last - 1].x - start.x()) / spacing));
    std::size_t next = first;
    for (std::int64_t i = iFirst; i <= iLast; ++i) {
      const double x = start.x() + double(i) * spacing;
      while (next < last && crossings[next].x <= x) winding -= crossings[next++].sign;
      if (winding == 0) continue;
      const Eigen::Vector3d point(x, y, z);
      if (surface.anyWithin(point, clearance)) continue;
      interior.push_back(point);
      if (surface.points().size() + interior.size() > maxParticles) {
        throwTooManyParticles(mesh.source, spacing, maxParticles, 0.0);
      }
    }
    first = last;
  }
  return interior;
}

}  // namespace sandphys::mesh_detail
