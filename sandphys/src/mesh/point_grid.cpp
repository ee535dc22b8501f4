#include "mesh/point_grid.h"

#include <algorithm>
#include <cmath>

namespace sandphys::mesh_detail {

PointGrid::PointGrid(double cellSize) : m_inverseCell(1.0 / cellSize) {}

std::size_t PointGrid::CellHash::operator()(const Cell& c) const {
  std::uint64_t h = std::uint64_t(c[0]) * 0x9E3779B97F4A7C15ull;
  h = (h ^ std::uint64_t(c[1])) * 0xBF58476D1CE4E5B9ull;
  h = (h ^ std::uint64_t(c[2])) * 0x94D049BB133111EBull;
  return std::size_t(h ^ (h >> 31));
}

PointGrid::Cell PointGrid::cellOf(const Eigen::Vector3d& p) const {
  // Clamped so that a far-off point cannot overflow the conversion; cells that far out are
  // merely shared.
  constexpr double kLimit = 4.0e18;
  Cell cell{};
  for (int i = 0; i < 3; ++i) {
    cell[i] = std::int64_t(std::clamp(std::floor(p(i) * m_inverseCell), -kLimit, kLimit));
  }
  return cell;
}

bool PointGrid::anyWithin(const Eigen::Vector3d& p, double radius) const {
  const Cell centre = cellOf(p);
  const double r2 = radius * radius;
  for (std::int64_t dz = -1; dz <= 1; ++dz) {
    for (std::int64_t dy = -1; dy <= 1; ++dy) {
      for (std::int64_t dx = -1; dx <= 1; ++dx) {
        auto it = m_cells.find({centre[0] + dx, centre[1] + dy, centre[2] + dz});
        if (it == m_cells.end()) continue;
        for (std::uint32_t i : it->second) {
          if ((m_points[i] - p).squaredNorm() <= r2) return true;
        }
      }
    }
  }
  return false;
}

bool PointGrid::addUnlessNear(const Eigen::Vector3d& p, double radius) {
  if (anyWithin(p, radius)) return false;
  m_cells[cellOf(p)].push_back(std::uint32_t(m_points.size()));
  m_points.push_back(p);
  return true;
}

}  // namespace sandphys::mesh_detail
