#pragma once

#include <cstddef>
#include <limits>
#include <span>
#include <vector>

#include "sandphys/analysis/fits.h"
#include "sandphys/math.h"

/// The angle of repose of a heap standing on a horizontal floor (Longmore et al. 2013, section
/// 6.1.4, Fig. 22), from the centres of its granules.
namespace sandphys::analysis {

/// How the heap's flank falls away from its top.
enum class HeapShape {
  /// A cone around a vertical axis (a heap poured from above): distance is from the axis.
  cone,
  /// A ridge along z (a heap fed from a slot that runs along z, or leaning on a wall along z, as
  /// in the paper's sump, Fig. 15): distance is |x - axisX| from the line x = axisX.
  ridge,
};

/// Where the heap stands and how its surface is sampled; lengths in m.
struct HeapSurfaceOptions {
  /// A cone or a ridge.
  HeapShape shape = HeapShape::cone;
  /// The heap's vertical axis (x, z); a ridge uses only axisX.
  double axisX = 0.0;
  double axisZ = 0.0;
  /// Height of the floor under the heap.
  double floorY = 0.0;
  /// Side of the square surface cells (x, z); > 0. About a granule's size: finer cells find
  /// holes between surface granules, coarser ones blur the flank.
  double binWidth = 0.02;
  /// Centres farther from the axis (or the ridge's line) are left out (grains that rolled off a
  /// floor's edge); > 0.
  double maxRadius = std::numeric_limits<double>::infinity();
  /// The flank is the surface between these fractions of the peak height above the floor
  /// (leaving out the rounded top and the toe, where grains roll out onto the floor);
  /// 0 <= flankFrom < flankTo <= 1.
  double flankFrom = 0.15;
  double flankTo = 0.85;
};

/// A heap's surface and the angle of its flank.
struct HeapAngle {
  /// Angle of the flank from the horizontal, degrees: atan of minus the fitted slope of height
  /// against distance from the axis (or the ridge's line).
  double degrees = 0.0;
  /// Highest surface point above the floor, m.
  double peakHeight = 0.0;
  /// Surface points on the flank: distance from the axis (or the ridge's line) and height above
  /// the floor, m.
  std::vector<double> radius;
  std::vector<double> height;
  /// fitLineRobust of height against radius over those points (bisquare weights, so that a
  /// grain resting on the flank or a hollow does not tilt the line).
  RobustLineFit fit;
  /// Surface cells found (every cell with a centre in it), flank or not.
  std::size_t surfaceCells = 0;
};

/// The surface of the heap is the highest centre in every cell of a square grid in x and z
/// (cells of equal area, so that the top of the heap is sampled as densely as its foot); the flank
/// is the part of it between flankFrom and flankTo of the peak height; the angle is that of a
/// robust line through the flank. The heap is assumed to be roughly a cone around the axis (a pile
/// poured from above it) or a ridge along z, as options.shape says. Throws InvalidArgument naming
/// the option or the centre that is not valid, or saying that the flank has fewer than 3 points (a
/// heap too small for the cells).
HeapAngle angleOfRepose(std::span<const Vec3> centres, const HeapSurfaceOptions& options = {});

}  // namespace sandphys::analysis
