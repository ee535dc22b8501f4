#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include <sandphys/sandphys.h>

#include "scenes/kit/course.h"
#include "scenes/kit/scene_with.h"
#include "scenes/scene.h"

namespace sandphys::scenes::kit {

/// Slowest emitter, m/s: a fresh layer has to clear the square before the next one starts.
inline constexpr float kMinPourSpeed = 0.5f;
/// Fastest emitter a scene accepts, m/s: beyond it the impacts overlap the grains by well over
/// the d/10 that the penetration guard allows; a wider emitter takes the rate more gently.
inline constexpr float kMaxPourSpeed = 3.0f;

/// A steady pour from square emitters at a height above a floor, as the pouring scenes
/// (sand-box-pour, repose-heap, dunes) set it up. The floor's top is at y = 0 for a box; a rough
/// floor has its particle centres there. Each emitter moves as slowly as its lattice can take the
/// rate, so that the grains fall as gently as the rate allows.
struct Pour {
  /// Particle diameter d, m.
  float d = 0.0f;
  /// Width of each emitter's square, d.
  float outlet = 0.0f;
  /// Height of the emitters' centres above the floor, d.
  float height = 0.0f;
  /// Granules/s of each emitter.
  float rate = 0.0f;
  /// Granules each emitter pours.
  std::uint32_t granules = 0;

  /// Half width of each emitter's square, m.
  float halfExtent() const { return 0.5f * outlet * d; }
  /// Downward speed of the emitted granules, m/s: a layer of emitterLayerGranules() slots leaves
  /// every spacing / speed seconds, with a margin so that float rounding never makes
  /// EmitterSettings refuse the rate; at least kMinPourSpeed.
  float speed() const;
  /// pourGuardSpeed of the pour's fall under the default gravity, m/s.
  float guardSpeed() const;
  /// Time for the last granule to land under gravity `g` (m/s²), with a margin for the grains to
  /// slide and bounce, s.
  double landingSeconds(double g) const;
  /// Throws InvalidArgument "`scene`: rate R granules/s needs the emitter's n slots to move at
  /// v m/s, more than 3 m/s; lower the rate or widen `widthName`" when speed() is over
  /// kMaxPourSpeed.
  void checkSpeed(std::string_view scene, std::string_view widthName) const;
  /// checkSpeed of an emitter whose width is "the outlet" over a rough floor; first throws
  /// InvalidArgument naming `scene` and "pour-height" when a granule has no room between the
  /// emitters and the floor.
  void checkAboveFloor(std::string_view scene) const;
  /// The emitter centred at x = `x` (m), z = 0, whose granules take their orientations from
  /// `seed`.
  EmitterSettings emitter(float x, std::uint64_t seed) const;
  /// The sink below a rough floor of half extent `floorHalfExtent` (m): everything that rolls off
  /// its edge (or, by a fault, through it) ends there.
  Sink sink(float floorHalfExtent) const;
  /// The course of a pour onto a floor: the pour is the act, from the first frame until the
  /// scene ends it; then the last granule lands (under gravity `g`, m/s²) and the sand is calm
  /// (below `settleSpeed`, m/s), or `maxSettleSeconds` more have passed.
  Course::Rule course(float settleSpeed, float maxSettleSeconds, double g) const;
  /// From the sink's top to a diameter above the emitters, over a floor of half extents
  /// `halfX`, `halfZ` (m).
  SceneBounds bounds(float halfX, float halfZ) const;
};

/// A Course whose act is a pour of `budget` granules: it counts them and ends the act once all
/// are poured.
class PourCourse : public Course {
 public:
  PourCourse() = default;
  /// `granuleMass`: kg (granuleMass()); `before`: granules in the World before the pour (a bed).
  PourCourse(const Rule& rule, float granuleMass, std::uint32_t budget, std::uint32_t before = 0)
      : Course(rule, granuleMass), m_budget(budget), m_before(before) {}

  /// After each frame, before update(): the granules poured by now; ends the act once all are.
  void count(const World& world, double simTime);
  /// Granules poured by the last count().
  std::uint32_t poured() const { return m_poured; }
  /// "pouring n/N", "settling", "settled" (calm) or "stopped" (the wait ran out).
  std::string status() const;

 private:
  std::uint32_t m_budget = 0;
  std::uint32_t m_before = 0;
  std::uint32_t m_poured = 0;
};

/// The base of a scene that pours: its Config describes the pour in the fields particleDiameter
/// (m), outlet and pourHeight (d), rate and granules (of each emitter), and the scene keeps its
/// course in m_course. The scene is finished when the course is done; it opens on its bounds.
template <class Config>
class PourScene : public SceneWith<Config> {
 public:
  using SceneWith<Config>::SceneWith;

  /// Counts the granules poured and updates the course for the granules alive.
  void update(World& world, const StepReport& report, double simTime) override {
    m_course.count(world, simTime);
    m_course.update(report, simTime);
  }
  bool finished() const override { return m_course.done(); }
  std::string status() const override { return m_course.status(); }
  /// The scene's bounds: the floor or box and the pour above it, where the sand gathers.
  SceneView view(const std::optional<SceneBounds>&) const override { return {this->bounds()}; }

 protected:
  /// The pour the Config describes.
  Pour pour() const {
    const Config& c = this->m_config;
    return {.d = c.particleDiameter,
            .outlet = c.outlet,
            .height = c.pourHeight,
            .rate = c.rate,
            .granules = c.granules};
  }

  PourCourse m_course;
};

/// Granules in one layer of a square emitter of half extent `halfExtent` (m) for particles of
/// diameter `particleDiameter` (m) (emitterLayerSlots).
std::uint32_t emitterLayerGranules(float halfExtent, float particleDiameter);

}  // namespace sandphys::scenes::kit
