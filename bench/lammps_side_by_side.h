#pragma once

// The benchmark's pile in LAMMPS, for --lammps-ranks: the same granules, material and time step
// (exportLammps), run for as many steps as sandphys was timed.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <sandphys/sandphys.h>

namespace sandphys::bench {

/// One LAMMPS run of a deck.
struct LammpsTiming {
  int ranks = 0;
  std::string deck;          ///< the deck's folder
  double loopSeconds = 0.0;  ///< LAMMPS's "Loop time" (its timesteps only), s; over all rounds
  std::uint64_t steps = 0;   ///< timesteps it ran, over all rounds
  /// Each round's loop time, s (MeasureOptions::lammpsRounds; one entry for one round).
  std::vector<double> roundLoopSeconds;
  std::string failure;  ///< why there is no time (empty: it ran)

  double millisecondsPerStep() const { return steps > 0 ? 1e3 * loopSeconds / double(steps) : 0.0; }
  double granuleStepsPerSecond(std::uint32_t granules) const {
    return loopSeconds > 0.0 ? double(granules) * double(steps) / loopSeconds : 0.0;
  }
};

/// Writes `world` into the folder `deck` as a deck that runs `steps` timesteps. Sync point.
void exportForLammps(const World& world, const std::filesystem::path& deck, std::uint32_t steps);

/// Runs the deck in timing.deck for `steps` timesteps of `timeStep` s on timing.ranks MPI ranks
/// and adds its loop time to `timing` as one more round; a run that fails, or leaves no loop
/// time, is named in LammpsTiming::failure, and a timing that holds a failure runs no more rounds.
void runLammpsRound(std::uint32_t steps, float timeStep, LammpsTiming& timing);

}  // namespace sandphys::bench
