#pragma once

// The benchmark's pile in LAMMPS, for --lammps-ranks: the same granules, material and time step
// (exportLammps), run for as many steps as sandphys was timed.
#include <filesystem>

#include <sandphys/sandphys.h>

#include "measure.h"

namespace sandphys::bench {

/// Writes `world` as timing starts into options.lammpsDir/<scene>-<granules>, a deck that runs
/// plan.steps timesteps; returns its folder (absolute). Sync point.
std::filesystem::path exportForLammps(const World& world, const SizePlan& plan,
                                      const MeasureOptions& options);

/// Runs the deck in `deck` for `seconds` of simulated time on `ranks` MPI ranks and reads its loop
/// time; a run that fails, or leaves no loop time, is named in LammpsTiming::failure.
LammpsTiming runLammps(const std::filesystem::path& deck, int ranks, double seconds);

}  // namespace sandphys::bench
