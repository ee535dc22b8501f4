#pragma once

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace sandphys::mesh_detail {

/// Points in a uniform hash grid, for "is any point within r of p?" with r up to the cell size.
/// Points keep the order they were added in: whatever the hash does, a sampler that adds them in
/// a fixed order gets the same result every time.
class PointGrid {
 public:
  explicit PointGrid(double cellSize);

  /// Adds `p` unless a point is within `radius` (<= cell size) of it; true if added.
  bool addUnlessNear(const Eigen::Vector3d& p, double radius);
  /// True if a point is within `radius` (<= cell size) of `p`.
  bool anyWithin(const Eigen::Vector3d& p, double radius) const;

  const std::vector<Eigen::Vector3d>& points() const { return m_points; }

 private:
  using Cell = std::array<std::int64_t, 3>;
  struct CellHash {
    std::size_t operator()(const Cell& c) const;
  };
  Cell cellOf(const Eigen::Vector3d& p) const;

  double m_inverseCell;
  std::vector<Eigen::Vector3d> m_points;
  std::unordered_map<Cell, std::vector<std::uint32_t>, CellHash> m_cells;
};

}  // namespace sandphys::mesh_detail
