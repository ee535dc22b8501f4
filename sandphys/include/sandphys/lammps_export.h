#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace sandphys {

class World;

/// How exportLammps writes its deck.
struct LammpsExportOptions {
  /// Simulated time the deck runs, s; > 0. The deck keeps it in an index variable, so that
  /// `lmp -in in.sandphys -var seconds 5` runs another span.
  double runSeconds = 1.0;
  /// Simulated time between two thermo lines and two trajectory frames, s; > 0.
  double outputSeconds = 0.01;
  /// Lines the caller adds to the deck's "not mapped" block: what drives the scene from outside
  /// the World (a sample's script, an engine's bodies), which the World cannot know.
  std::vector<std::string> notes;
};

/// What exportLammps wrote.
struct LammpsExportSummary {
  std::filesystem::path deck;     ///< DIR/in.sandphys, the input deck (`lmp -in in.sandphys`)
  std::uint32_t clumps = 0;       ///< rigid clumps: alive granules and dynamic bodies
  std::uint32_t clumpAtoms = 0;   ///< their particles
  std::uint32_t frozenAtoms = 0;  ///< particles of static and kinematic bodies, frozen
  std::uint32_t walls = 0;        ///< colliders written as granular region walls
  std::uint32_t sinks = 0;        ///< sinks written as deletion regions
  /// The deck's "not mapped" block, a line each: what became something else, and what is missing.
  std::vector<std::string> notMapped;
};

/// Writes a LAMMPS input deck of `world`'s current state into `directory` (created if needed):
/// in.sandphys (the deck), sandphys.data (every particle as a sphere) and bodies.rigid (each
/// clump's mass, centre of mass, inertia tensor, velocity and angular momentum, for fix
/// rigid/small's infile). Granules and dynamic bodies become rigid clumps, static and kinematic
/// bodies frozen particles, colliders granular region walls, sinks regions whose clumps are
/// deleted; the material, gravity and time step carry over one to one (docs/lammps.md). The deck
/// runs with `lmp -in in.sandphys` and with `mpirun -np N lmp -in in.sandphys`; it writes
/// log.lammps, traj.dump and, at its end, final.dump (every particle) and final_pairs.dump (the
/// distance of every particle pair closer than a diameter). Sync point (reads the bodies and
/// particles back). Throws InvalidArgument for options out of range and Error naming the file
/// that cannot be written.
LammpsExportSummary exportLammps(const World& world, const std::filesystem::path& directory,
                                 const LammpsExportOptions& options = {});

}  // namespace sandphys
