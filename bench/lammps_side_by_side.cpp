#include "lammps_side_by_side.h"

namespace sandphys::bench {

void exportForLammps(const World& world, const std::filesystem::path& deck, std::uint32_t steps) {
  const double seconds = double(steps) * double(world.timeStep());
  exportLammps(world, deck, {.runSeconds = seconds, .outputSeconds = seconds});
}

LammpsTiming runLammps(const std::filesystem::path& deck, int ranks, std::uint32_t steps,
                       float timeStep) {
  LammpsTiming timing{.ranks = ranks, .deck = deck.string()};
  try {
    const LammpsRun run = runLammpsDeck(deck, ranks, double(steps) * double(timeStep));
    timing.loopSeconds = run.loopSeconds;
    timing.steps = run.loopSteps;
    if (run.loopSteps == 0) timing.failure = (deck / "log.lammps").string() + " has no loop time";
  } catch (const Error& error) {
    timing.failure = error.what();
  }
  return timing;
}

}  // namespace sandphys::bench
