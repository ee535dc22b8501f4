#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "sandphys/math.h"

namespace sandphys {

/// One thermo line of a deck exportLammps wrote (its `thermo_style`).
struct LammpsThermo {
  double step = 0.0;
  double time = 0.0;             ///< simulated since the export, s
  double atoms = 0.0;            ///< particles present
  double kineticEnergy = 0.0;    ///< of the clumps, translation and rotation, J
  double contacts = 0.0;         ///< particle pairs in contact
  double meanNormalForce = 0.0;  ///< over those pairs, N
};

/// What a run of such a deck left in its folder.
struct LammpsRun {
  std::string version;               ///< LAMMPS's version line ("LAMMPS (29 Sep 2021 ...)")
  std::vector<LammpsThermo> thermo;  ///< every thermo line, step 0 included
  /// Each clump's centre in final.dump, in molecule order: the mean of its particles, which for
  /// a granule is its centre of mass.
  std::vector<Vec3> clumpCentres;
  /// The run's "Loop time of T on P procs for N steps" line: the wall time of its timesteps, s,
  /// its MPI ranks and its timesteps (0, 0, 0 when the log holds no such line).
  double loopSeconds = 0.0;
  int loopRanks = 0;
  std::uint64_t loopSteps = 0;
};

/// The shell command that runs the deck in `directory` for `seconds` of simulated time on
/// `ranks` MPI ranks (1: lmp alone, else mpirun, which as root gets --allow-run-as-root), its
/// output going to lammps.out there. Needs `lmp` (and `mpirun`) on the PATH (Debian: lammps,
/// openmpi-bin).
std::string lammpsCommand(const std::filesystem::path& directory, int ranks, double seconds);

/// Reads log.lammps and final.dump from `directory`. Throws Error naming the file when one is
/// missing or holds no thermo line or no particle.
LammpsRun readLammpsRun(const std::filesystem::path& directory);

/// Runs lammpsCommand(directory, ranks, seconds) and returns readLammpsRun(directory). Throws
/// Error naming the command, its exit status and lammps.out when the command fails.
LammpsRun runLammpsDeck(const std::filesystem::path& directory, int ranks, double seconds);

}  // namespace sandphys
