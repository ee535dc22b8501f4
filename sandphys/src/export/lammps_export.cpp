// exportLammps: the deck, the data file and the clumps' infile (docs/lammps.md says what maps to
// what and why).
#include "sandphys/lammps_export.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>

#include "core/validation.h"
#include "core/world_access.h"
#include "export/lammps_deck.h"
#include "export/lammps_scene.h"
#include "export/lammps_text.h"

namespace sandphys {

using namespace detail;

namespace {

std::ofstream openFile(const std::filesystem::path& path) {
  std::ofstream out(path);
  if (!out) throw Error("exportLammps: cannot write '" + path.string() + "'");
  out.imbue(std::locale::classic());
  return out;
}

void closeFile(std::ofstream& out, const std::filesystem::path& path) {
  out.close();
  if (!out) throw Error("exportLammps: writing '" + path.string() + "' failed");
}

// sandphys.data: every particle as a sphere of atom_style hybrid sphere molecular (id type x y z
// diameter density molecule); type 1 for the clumps' particles, 2 for the frozen ones.
void writeData(const std::filesystem::path& path, const LammpsScene& scene, double diameter,
               const std::array<Vec3d, 2>& box) {
  std::ofstream out = openFile(path);
  out << "sandphys World: " << scene.clumps.size() << " rigid clumps, "
      << scene.atoms.size() - scene.clumpAtoms << " frozen particles\n\n"
      << scene.atoms.size() << " atoms\n2 atom types\n\n";
  const char* axes[] = {"x", "y", "z"};
  for (int k = 0; k < 3; ++k) {
    out << lammpsNumber(box[0][k]) << ' ' << lammpsNumber(box[1][k]) << ' ' << axes[k] << "lo "
        << axes[k] << "hi\n";
  }
  out << "\nAtoms # hybrid\n\n";
  const double volume = std::numbers::pi * diameter * diameter * diameter / 6.0;
  for (std::size_t i = 0; i < scene.atoms.size(); ++i) {
    const LammpsAtom& a = scene.atoms[i];
    out << i + 1 << ' ' << (a.molecule > 0 ? 1 : 2) << ' ' << lammpsNumber(a.position[0]) << ' '
        << lammpsNumber(a.position[1]) << ' ' << lammpsNumber(a.position[2]) << ' '
        << lammpsNumber(diameter) << ' ' << lammpsNumber(a.mass / volume) << ' ' << a.molecule
        << '\n';
  }
  closeFile(out, path);
}

// bodies.rigid: fix rigid/small's infile, a line per clump in molecule order. fix rigid/small's
// gravity keyword gives the first step only half of gravity's kick (measured: a clump falling
// from rest is 0.5 dt g slow ever after), so each velocity carries that half kick in advance.
void writeBodies(const std::filesystem::path& path, const LammpsScene& scene, double dt,
                 Vec3 gravity) {
  const Vec3d kick{0.5 * dt * gravity.x, 0.5 * dt * gravity.y, 0.5 * dt * gravity.z};
  std::ofstream out = openFile(path);
  out << "# molecule mass xcm ycm zcm ixx iyy izz ixy ixz iyz vxcm vycm vzcm lx ly lz ixcm iycm "
         "izcm (sandphys body slot in the data file's order: molecule k is the k-th clump)\n"
      << scene.clumps.size() << '\n';
  for (std::size_t k = 0; k < scene.clumps.size(); ++k) {
    const LammpsClump& c = scene.clumps[k];
    out << k + 1 << ' ' << lammpsNumber(c.mass);
    for (double v : c.centre) out << ' ' << lammpsNumber(v);
    for (double v : c.inertia) out << ' ' << lammpsNumber(v);
    for (int i = 0; i < 3; ++i) out << ' ' << lammpsNumber(c.velocity[i] + kick[i]);
    for (double v : c.angularMomentum) out << ' ' << lammpsNumber(v);
    out << " 0 0 0\n";
  }
  closeFile(out, path);
}

}  // namespace

LammpsExportSummary exportLammps(const World& world, const std::filesystem::path& directory,
                                 const LammpsExportOptions& options) {
  requirePositive("LammpsExportOptions.runSeconds", options.runSeconds, "(s)");
  requirePositive("LammpsExportOptions.outputSeconds", options.outputSeconds, "(s)");
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (error) {
    throw Error("exportLammps: cannot create the folder '" + directory.string() +
                "': " + error.message());
  }
  const LammpsScene scene = gatherLammpsScene(world);
  const LammpsDeck deck = composeLammpsDeck(world, scene, options);

  writeData(directory / "sandphys.data", scene, world.settings().particleDiameter, deck.box);
  writeBodies(directory / "bodies.rigid", scene, world.contactModel().timeStep,
              world.settings().gravity);
  LammpsExportSummary summary;
  summary.deck = directory / "in.sandphys";
  std::ofstream out = openFile(summary.deck);
  out << deck.text;
  closeFile(out, summary.deck);
  summary.clumps = static_cast<std::uint32_t>(scene.clumps.size());
  summary.clumpAtoms = scene.clumpAtoms;
  summary.frozenAtoms = static_cast<std::uint32_t>(scene.atoms.size()) - scene.clumpAtoms;
  summary.walls = deck.walls;
  summary.sinks = deck.sinks;
  summary.notMapped = deck.notMapped;
  return summary;
}

}  // namespace sandphys
