// The angle of repose from a heap's surface granules (a square grid of highest centres, then a
// robust line through the flank).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <string>
#include <utility>

#include "analysis/input_checks.h"
#include "sandphys/analysis/heap.h"
#include "sandphys/error.h"

namespace sandphys::analysis {

namespace {

constexpr const char* kFunction = "angleOfRepose";

[[noreturn]] void badOption(const char* name, double value, const char* rule) {
  throw InvalidArgument(std::string(kFunction) + ": options." + name + " is " +
                        detail::numberText(value) + "; it must be " + rule);
}

void checkOptions(const HeapSurfaceOptions& o) {
  if (!std::isfinite(o.axisX)) badOption("axisX", o.axisX, "finite");
  if (!std::isfinite(o.axisZ)) badOption("axisZ", o.axisZ, "finite");
  if (!std::isfinite(o.floorY)) badOption("floorY", o.floorY, "finite");
  if (!(o.binWidth > 0.0) || !std::isfinite(o.binWidth)) {
    badOption("binWidth", o.binWidth, "finite and > 0");
  }
  if (!(o.maxRadius > 0.0)) badOption("maxRadius", o.maxRadius, "> 0");
  if (!(o.flankFrom >= 0.0 && o.flankFrom < o.flankTo && o.flankTo <= 1.0)) {
    throw InvalidArgument(std::string(kFunction) + ": options.flankFrom " +
                          detail::numberText(o.flankFrom) + " and flankTo " +
                          detail::numberText(o.flankTo) +
                          " must satisfy 0 <= flankFrom < flankTo <= 1");
  }
}

}  // namespace

HeapAngle angleOfRepose(std::span<const Vec3> centres, const HeapSurfaceOptions& options) {
  checkOptions(options);
  for (std::size_t i = 0; i < centres.size(); ++i) {
    const Vec3& c = centres[i];
    if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.z)) {
      throw InvalidArgument(std::string(kFunction) + ": centres[" + std::to_string(i) + "] is (" +
                            detail::numberText(c.x) + ", " + detail::numberText(c.y) + ", " +
                            detail::numberText(c.z) + "), not a finite point");
    }
  }
  // Highest centre of each cell of the grid, keyed by its (x, z) cell index.
  struct Cell {
    double height = 0.0;
    double radius = 0.0;
  };
  std::map<std::pair<std::int64_t, std::int64_t>, Cell> cells;
  for (const Vec3& c : centres) {
    const double dx = c.x - options.axisX;
    const double dz = c.z - options.axisZ;
    const double r = options.shape == HeapShape::ridge ? std::abs(dx) : std::hypot(dx, dz);
    if (r > options.maxRadius) continue;
    const std::pair<std::int64_t, std::int64_t> key{
        static_cast<std::int64_t>(std::floor(dx / options.binWidth)),
        static_cast<std::int64_t>(std::floor(dz / options.binWidth))};
    const double h = c.y - options.floorY;
    auto [cell, added] = cells.try_emplace(key, Cell{h, r});
    if (!added && h > cell->second.height) cell->second = {h, r};
  }

  HeapAngle result;
  result.surfaceCells = cells.size();
  for (const auto& [key, cell] : cells)
    result.peakHeight = std::max(result.peakHeight, cell.height);
  const double low = options.flankFrom * result.peakHeight;
  const double high = options.flankTo * result.peakHeight;
  // The flank is first the cells whose height lies in the band. That choice is biased: near the
  // band's top edge it keeps the cells that lie low and near its foot the ones that lie high,
  // which flattens the line. So the band only finds the first line; the flank is then chosen by
  // radius, between where the line crosses the band's edges, and fitted again until the choice
  // settles (a choice along x does not bias a fit of y).
  auto inBand = [&](const Cell& cell) { return cell.height >= low && cell.height <= high; };
  auto collect = [&](auto keep) {
    result.radius.clear();
    result.height.clear();
    for (const auto& [key, cell] : cells) {
      if (!keep(cell)) continue;
      result.radius.push_back(cell.radius);
      result.height.push_back(cell.height);
    }
    if (result.radius.size() < 3) {
      throw InvalidArgument(std::string(kFunction) + ": " + std::to_string(result.radius.size()) +
                            " surface cells lie on the flank (between " + detail::numberText(low) +
                            " and " + detail::numberText(high) + " m above the floor, of a peak " +
                            detail::numberText(result.peakHeight) + " m high, in " +
                            std::to_string(result.surfaceCells) +
                            " cells), at least 3 needed: the heap is too small for cells " +
                            detail::numberText(options.binWidth) + " m wide");
    }
    result.fit = fitLineRobust(result.radius, result.height);
  };
  collect(inBand);
  constexpr int kMaxRounds = 10;
  for (int round = 0; round < kMaxRounds; ++round) {
    const LineFit& line = result.fit.line;
    if (!(line.slope < 0.0)) break;  // no flank falling outward: nothing to refine
    const double inner = (high - line.intercept) / line.slope;
    const double outer = (low - line.intercept) / line.slope;
    const std::vector<double> previous = result.radius;
    collect([&](const Cell& cell) { return cell.radius >= inner && cell.radius <= outer; });
    if (result.radius == previous) break;
  }
  result.degrees = std::atan(-result.fit.line.slope) * 180.0 / std::numbers::pi;
  return result;
}

}  // namespace sandphys::analysis
