#pragma once

#include <string>

#include "sandphys/settings.h"

namespace sandphys::detail {

/// The stiffness check of ContactLaw::HertzMindlin: throws InvalidArgument naming E, maxSpeed,
/// the peak overlap and the E (or speed) that would do when `peakOverlap` (m) exceeds
/// `passOverlap` particle diameters; `what` says which impact it is.
void requireNoPassThrough(const WorldSettings& settings, double peakOverlap, double passOverlap,
                          const std::string& what);

}  // namespace sandphys::detail
