#pragma once

#include <cstdint>

#include <sandphys/sandphys.h>

namespace sandphys::scenes::kit {

/// A wait for the sand to settle that starts at `start` (s of simulated time): over once at least
/// `minSeconds` have passed and the sand is calm, or `maxSeconds` have passed whatever it does.
struct SettleWait {
  double start = 0.0;
  double minSeconds = 0.0;
  double maxSeconds = 0.0;

  bool over(bool calm, double simTime) const {
    const double since = simTime - start;
    return since >= minSeconds && (calm || since >= maxSeconds);
  }
};

/// The course most scenes take: the sand settles (Settling), the scene acts once it has (removes
/// a wall, opens a gate, pushes a blade, pours: Acting, for as long as the scene says), the sand
/// settles again (Resting), and the scene is done. "Calm" is granulesCalm: the world's kinetic
/// energy per granule below that of one granule at the settle speed.
class Course {
 public:
  enum class Phase { Settling, Acting, Resting, Done };

  struct Rule {
    /// Calm below this rms speed, m/s.
    float settleSpeed = 0.0f;
    /// Longest wait of each settle, s from its start.
    double maxSettleSeconds = 0.0;
    /// The first settle starts at this simulated time (the act comes no earlier), s.
    double actAfter = 0.0;
    /// The sand rests at least this long after the act before it may count as calm, s.
    double minRestSeconds = 0.0;
    /// Longest rest after the act, s (maxSettleSeconds when negative).
    double maxRestSeconds = -1.0;
    /// Start acting at once, without a first settle (a pour).
    bool actFirst = false;
  };

  Course() = default;
  /// `granuleMass`: kg, of one granule (granuleMass()).
  Course(const Rule& rule, float granuleMass);

  /// After each frame: `report` is its step's (its stats tell the kinetic energy), `granules` the
  /// granules it is shared among. Ends a settle that is over (Settling → Acting, Resting →
  /// Done). True on the frame the phase changed.
  bool update(const StepReport& report, double simTime, std::uint32_t granules);
  /// update() for the granules alive in the report's stats (a pour, a flow into a sink).
  bool update(const StepReport& report, double simTime) {
    return update(report, simTime, report.stats.granulesAlive);
  }
  /// The scene's act is over (an instant act calls it at once): Acting → Resting.
  void endAct(double simTime);

  Phase phase() const { return m_phase; }
  bool acting() const { return m_phase == Phase::Acting; }
  bool done() const { return m_phase == Phase::Done; }
  /// Simulated time the act started and ended, s; negative before.
  double actStart() const { return m_actStart; }
  double actEnd() const { return m_actEnd; }
  /// Whether the sand was calm when the last settle ended (false when its wait ran out).
  bool calm() const { return m_calm; }

 private:
  Rule m_rule;
  float m_granuleMass = 0.0f;
  Phase m_phase = Phase::Settling;
  double m_actStart = -1.0;
  double m_actEnd = -1.0;
  bool m_calm = false;
};

/// Whether `granules` granules of mass `granuleMass` (kg) are calm after the step that gave
/// `report`: the world's kinetic energy (from the step's stats) per granule is below that of one
/// granule moving at `settleSpeed` (m/s). False without per-frame stats (a scene's time limits
/// apply then) or without granules.
bool granulesCalm(const StepReport& report, std::uint32_t granules, float granuleMass,
                  float settleSpeed);
/// Time a body needs to fall `height` (m; none when <= 0) starting at `speed` (m/s, downward)
/// under gravity `g` (m/s²), s.
double fallTime(double height, double speed, double g);

}  // namespace sandphys::scenes::kit
