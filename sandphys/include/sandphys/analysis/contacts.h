#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "sandphys/math.h"

/// Structure of a packing's contact network (Longmore et al. 2013, section 6.1.2, Figs. 18-20):
/// how forces correlate in space, which way contacts point, and how the contacts split into
/// weak and strong networks. Double precision; bad input throws sandphys::InvalidArgument naming
/// the function and the problem.
namespace sandphys::analysis {

/// The force-force spatial correlation g(r) on distance bins.
struct ForceCorrelation {
  /// Bin centres, m.
  std::vector<double> distance;
  /// ⟨f_i f_j⟩ over the pairs of different contacts whose points lie in the bin's distance
  /// range, over ⟨f⟩² of all contacts: 1 where forces are uncorrelated, above 1 where strong
  /// forces sit near strong ones. 0 for a bin without pairs.
  std::vector<double> correlation;
  /// Pairs in each bin.
  std::vector<std::size_t> pairs;
};

/// g(r) of the contact forces `forces` at the contact points `points`, on bins of `binWidth` from
/// 0 to `maxDistance` (m, both > 0). Needs at least 2 contacts, as many forces as points, all
/// finite, and forces whose mean is > 0.
ForceCorrelation forceCorrelation(std::span<const Vec3> points, std::span<const double> forces,
                                  double binWidth, double maxDistance);

/// The distribution of contact directions by elevation: the angle between a contact's normal
/// and the horizontal plane, 0° (the contact pushes sideways) to 90° (it pushes up or down).
struct AngleDistribution {
  /// Bin centres, degrees.
  std::vector<double> degrees;
  /// Probability density per degree in each bin (it integrates to 1 over 0..90°).
  std::vector<double> density;
  /// The density contacts pointing in uniformly random directions would have in each bin
  /// (∝ cos of the elevation), for comparison.
  std::vector<double> isotropic;
};

/// The elevation distribution of `normals` (need not be unit; y is up) on `bins` equal bins over
/// 0..90° (bins >= 1). Needs at least 1 normal, each finite and non-zero.
AngleDistribution contactAngles(std::span<const Vec3> normals, int bins = 9);

/// The weak and strong networks (after Silbert et al., the paper's Fig. 20): for each threshold
/// f_cut, the fraction of contacts whose force is above f_cut (normalised forces, mean 1, so
/// that f_cut = 1 splits weak from strong).
struct NetworkFractions {
  std::vector<double> threshold;
  /// Fraction of the contacts with f > threshold.
  std::vector<double> contacts;
  /// Fraction of the total force those contacts carry.
  std::vector<double> force;
};

/// NetworkFractions of `forces` (normalised by their mean here) at thresholds 0, step, 2 step,
/// ... up to maxThreshold (step > 0, maxThreshold >= 0). Needs forces as for normalisedByMean.
NetworkFractions networkFractions(std::span<const double> forces, double step = 0.1,
                                  double maxThreshold = 4.0);

}  // namespace sandphys::analysis
