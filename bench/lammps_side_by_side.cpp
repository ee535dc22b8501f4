#include "lammps_side_by_side.h"

#include <cstdlib>
#include <string>

namespace sandphys::bench {

std::filesystem::path exportForLammps(const World& world, const SizePlan& plan,
                                      const MeasureOptions& options) {
  const std::filesystem::path deck =
      std::filesystem::absolute(options.lammpsDir) /
      (std::string(benchSceneName(options.scene)) + "-" + std::to_string(plan.granules));
  const double seconds = double(plan.steps) * double(world.timeStep());
  exportLammps(world, deck, {.runSeconds = seconds, .outputSeconds = seconds});
  return deck;
}

LammpsTiming runLammps(const std::filesystem::path& deck, int ranks, double seconds) {
  LammpsTiming timing{.ranks = ranks, .deck = deck.string()};
  const std::string command = lammpsCommand(deck, ranks, seconds);
  if (const int status = std::system(command.c_str()); status != 0) {
    timing.failure = "`" + command + "` failed with status " + std::to_string(status) + " (see " +
                     (deck / "lammps.out").string() + ")";
    return timing;
  }
  try {
    const LammpsRun run = readLammpsRun(deck);
    timing.loopSeconds = run.loopSeconds;
    timing.steps = run.loopSteps;
    if (run.loopSteps == 0) timing.failure = (deck / "log.lammps").string() + " has no loop time";
  } catch (const Error& error) {
    timing.failure = error.what();
  }
  return timing;
}

}  // namespace sandphys::bench
