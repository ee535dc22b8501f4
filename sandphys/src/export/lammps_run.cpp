#include "sandphys/lammps_run.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

#include "sandphys/error.h"

namespace sandphys {

namespace {

std::ifstream open(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw Error("readLammpsRun: cannot read '" + path.string() + "'");
  return in;
}

}  // namespace

std::string lammpsCommand(const std::filesystem::path& directory, int ranks, double seconds) {
  char span[32];
  std::snprintf(span, sizeof span, "%.9g", seconds);
  std::string command = "cd '" + directory.string() + "' && ";
  if (ranks > 1) {
    command += "mpirun " + std::string(::geteuid() == 0 ? "--allow-run-as-root " : "") +
               "--oversubscribe -np " + std::to_string(ranks) + ' ';
  }
  return command + "lmp -in in.sandphys -var seconds " + span + " > lammps.out 2>&1";
}

LammpsRun readLammpsRun(const std::filesystem::path& directory) {
  LammpsRun run;
  std::ifstream log = open(directory / "log.lammps");
  std::string line;
  bool thermo = false;
  while (std::getline(log, line)) {
    if (run.version.empty() && line.rfind("LAMMPS (", 0) == 0) run.version = line;
    if (line.rfind("Step Time Atoms v_energy", 0) == 0) {
      thermo = true;
      continue;
    }
    if (line.rfind("Loop time of ", 0) == 0) {
      thermo = false;
      // "Loop time of T on P procs for N steps with A atoms"
      std::istringstream words(line);
      std::string word;
      double seconds = 0.0;
      int ranks = 0;
      std::uint64_t steps = 0;
      words >> word >> word >> word >> seconds >> word >> ranks >> word >> word >> steps;
      if (words) {
        run.loopSeconds = seconds;
        run.loopRanks = ranks;
        run.loopSteps = steps;
      }
    }
    if (!thermo) continue;
    std::istringstream fields(line);
    LammpsThermo t;
    fields >> t.step >> t.time >> t.atoms >> t.kineticEnergy >> t.contacts >> t.meanNormalForce;
    if (fields) run.thermo.push_back(t);  // not a warning inside the block
  }
  if (run.thermo.empty()) {
    throw Error("readLammpsRun: '" + (directory / "log.lammps").string() +
                "' holds no thermo line of a deck exportLammps wrote");
  }
  // final.dump: id mol type x y z vx vy vz; a clump's particles have its molecule, > 0.
  std::ifstream dump = open(directory / "final.dump");
  std::map<long, std::pair<Vec3, int>> clumps;
  bool atoms = false;
  while (std::getline(dump, line)) {
    if (line.rfind("ITEM: ATOMS", 0) == 0) {
      atoms = true;
      continue;
    }
    if (!atoms) continue;
    std::istringstream fields(line);
    long id = 0, molecule = 0;
    int type = 0;
    double x = 0.0, y = 0.0, z = 0.0;
    fields >> id >> molecule >> type >> x >> y >> z;
    if (!fields || molecule <= 0) continue;
    auto& [sum, count] = clumps[molecule];
    sum += Vec3{float(x), float(y), float(z)};
    ++count;
  }
  if (!atoms) {
    throw Error("readLammpsRun: '" + (directory / "final.dump").string() + "' holds no particles");
  }
  for (const auto& [molecule, clump] : clumps) {
    run.clumpCentres.push_back(clump.first / float(clump.second));
  }
  return run;
}

LammpsRun runLammpsDeck(const std::filesystem::path& directory, int ranks, double seconds) {
  const std::string command = lammpsCommand(directory, ranks, seconds);
  if (const int status = std::system(command.c_str()); status != 0) {
    throw Error("`" + command + "` failed with status " + std::to_string(status) + " (see " +
                (directory / "lammps.out").string() + ")");
  }
  return readLammpsRun(directory);
}

}  // namespace sandphys
