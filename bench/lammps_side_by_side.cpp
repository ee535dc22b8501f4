#include "lammps_side_by_side.h"

namespace sandphys::bench {

void exportForLammps(const World& world, const std::filesystem::path& deck, std::uint32_t steps) {
  const double seconds = double(steps) * double(world.timeStep());
  exportLammps(world, deck, {.runSeconds = seconds, .outputSeconds = seconds});
}

void runLammpsRound(std::uint32_t steps, float timeStep, LammpsTiming& timing) {
  if (!timing.failure.empty()) return;
  const std::filesystem::path deck = timing.deck;
  try {
    const LammpsRun run = runLammpsDeck(deck, timing.ranks, double(steps) * double(timeStep));
    if (run.loopSteps == 0) {
      timing.failure = (deck / "log.lammps").string() + " has no loop time";
      return;
    }
    timing.loopSeconds += run.loopSeconds;
    timing.steps += run.loopSteps;
    timing.roundLoopSeconds.push_back(run.loopSeconds);
  } catch (const Error& error) {
    timing.failure = error.what();
  }
}

}  // namespace sandphys::bench
