// The bulldozer scene at a small size: a block of 8 x 3 x 8 = 192 granules slumps against the
// idle kinematic blade (no gap) for 0.8 s, then the blade pushes it 20 d at 0.5 m/s and stops.
// One run of 2 s simulated is shared by the tests below; the numbers quoted in them are from that
// run on llvmpipe.
//
// The sand's momentum closes the checks on the blade's force. Over any span of substeps, for the
// granules (mass M, momentum P), with J the blade's impulse on the sand (minus what
// World::takeBodyForces sums for the blade) and F the floor's force on the sand:
//   ΔP = J + ∫F dt + M g T   (semi-implicit Euler adds dt · force to each granule's momentum, and
//                             the speed guard, which would break this, never fires here).
// The floor is a horizontal plane, so F_y is the sum of its contacts' normal forces, and each
// contact's friction is capped at μ times its normal force, hence:
//   |ΔP_x - J_x| = |∫F_x dt| <= μ ∫F_y dt = μ (ΔP_y - J_y + M g T).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "scenes/bulldozer.h"
#include "scenes/kit/geometry.h"
#include "scenes/kit/settings.h"
#include "support/scene_metric.h"
#include "support/test_world.h"

namespace sandphys::scenes {
namespace {

using Phase = Bulldozer::Phase;

constexpr float kFrame = 1.0f / 60.0f;
constexpr double kG = 9.81;
constexpr float kPushStart = 0.8f;      // s
constexpr float kPushDistance = 20.0f;  // d
constexpr float kBladeSpeed = 0.5f;     // m/s
// The push ends at 1.6 s; the rest lets the sand stop.
constexpr double kRunSeconds = 2.0;
// The stillness check before the push looks at this last stretch of the wait, s.
constexpr double kStillSeconds = 0.1;

struct Momentum {
  double x = 0.0;     // N s
  double y = 0.0;     // N s
  double mass = 0.0;  // kg
};

Momentum momentum(const std::vector<BodyState>& bodies, float granuleMass) {
  Momentum p;
  for (const BodyState& body : bodies) {
    if (!body.granule || !body.alive) continue;
    p.x += granuleMass * static_cast<double>(body.velocity.x);
    p.y += granuleMass * static_cast<double>(body.velocity.y);
    p.mass += granuleMass;
  }
  return p;
}

// Mean x of the granules, m.
double comX(const std::vector<BodyState>& bodies) {
  double sum = 0.0;
  std::size_t count = 0;
  for (const BodyState& body : bodies) {
    if (!body.granule || !body.alive) continue;
    sum += body.position.x;
    ++count;
  }
  return count ? sum / static_cast<double>(count) : 0.0;
}

// Both sides of the Coulomb bound above over one phase of the run.
struct Balance {
  double floorX = 0.0;  // ∫F_x dt, N s
  double normal = 0.0;  // ∫F_y dt, N s
  double seconds = 0.0;
  double bladeX = 0.0;  // J_x, N s
};

class BulldozerRun : public ::testing::Test {
 protected:
  struct BladeSample {
    std::uint64_t step = 0;  // World::stepCount when read
    SceneBody blade;
  };

  static void SetUpTestSuite() {
    s_scene = std::make_unique<Bulldozer>();
    Bulldozer::Config& config = s_scene->config();
    config.berm = {8, 3, 8};
    config.gap = 0.0f;
    config.pushStart = kPushStart;
    config.pushDistance = kPushDistance;
    config.bladeSpeed = kBladeSpeed;
    s_world = std::make_unique<World>(testing::gpu(), s_scene->settings());
    s_scene->build(*s_world);
    s_start = s_world->readBodies();
    int frame = 0;
    while (s_world->simulatedTime() < kRunSeconds) {
      const StepReport report = s_scene->step(*s_world, kFrame);
      s_scene->update(*s_world, report, s_world->simulatedTime());
      s_velocityClamps = report.stats.velocityClamps;
      if (s_still.empty() && s_scene->phase() == Phase::Waiting &&
          s_world->simulatedTime() >= kPushStart - kStillSeconds) {
        s_still = s_world->readBodies();
        s_stillFromSample = s_scene->dragSeries().size();
      }
      if (++frame % 3 == 0) {
        s_path.push_back({s_world->stepCount(), s_scene->bodies(*s_world).at(0)});
      }
      if (frame % 6 == 0) {
        std::printf("t %.2f s (%s): kinetic energy %.3g J\n", s_world->simulatedTime(),
                    s_scene->status().c_str(), report.stats.kineticEnergy);
      }
    }
    s_end = s_world->readBodies();
  }
  static void TearDownTestSuite() {
    s_scene.reset();
    s_world.reset();
  }

  static const Bulldozer& scene() { return *s_scene; }
  static float d() { return s_scene->config().particleDiameter; }
  static float granuleMass() { return kit::granuleMass(s_world->settings()); }
  static double weight() { return momentum(s_end, granuleMass()).mass * kG; }

  // The bound's terms over `phase`, between the bodies read at its start and at its end.
  static Balance balance(Phase phase, const std::vector<BodyState>& from,
                         const std::vector<BodyState>& to) {
    const Momentum p0 = momentum(from, granuleMass());
    const Momentum p1 = momentum(to, granuleMass());
    const Bulldozer::BladeLoad& load = scene().load(phase);
    Balance b;
    b.seconds = static_cast<double>(load.substeps) * s_world->timeStep();
    b.bladeX = -load.impulse[0];
    b.floorX = (p1.x - p0.x) - b.bladeX;
    b.normal = (p1.y - p0.y) + load.impulse[1] + p1.mass * kG * b.seconds;
    return b;
  }

  static std::unique_ptr<Bulldozer> s_scene;
  static std::unique_ptr<World> s_world;
  static std::vector<BodyState> s_start;
  static std::vector<BodyState> s_still;  // kStillSeconds before the push
  static std::size_t s_stillFromSample;   // first drag sample after s_still
  static std::vector<BodyState> s_end;
  static std::vector<BladeSample> s_path;
  static std::uint64_t s_velocityClamps;
};

std::unique_ptr<Bulldozer> BulldozerRun::s_scene;
std::unique_ptr<World> BulldozerRun::s_world;
std::vector<BodyState> BulldozerRun::s_start;
std::vector<BodyState> BulldozerRun::s_still;
std::size_t BulldozerRun::s_stillFromSample = 0;
std::vector<BodyState> BulldozerRun::s_end;
std::vector<BulldozerRun::BladeSample> BulldozerRun::s_path;
std::uint64_t BulldozerRun::s_velocityClamps = 0;

// The kinematic blade is where its path puts it at every reading, within float rounding, and ends
// exactly pushDistance from its start; the sand does not turn it or lift it.
TEST_F(BulldozerRun, BladeKeepsExactlyToItsPath) {
  const Vec3 start = scene().bladeStart();
  const double travel = scene().bladeTravel();
  ASSERT_FLOAT_EQ(static_cast<float>(travel), kPushDistance * d());
  const std::uint64_t first = scene().pushStartStep(), steps = scene().pushSteps();
  // A whole number of substeps at a speed within a hair of the one asked for.
  const double speed = travel / (static_cast<double>(steps) * s_world->timeStep());
  EXPECT_NEAR(speed, kBladeSpeed, 1e-3 * kBladeSpeed);
  EXPECT_EQ(scene().load(Phase::Pushing).substeps, steps);
  EXPECT_EQ(scene().load(Phase::Waiting).substeps, first);
  ASSERT_EQ(scene().phase(), Phase::Stopped);
  // The blade is a closed shell (so it has the solid's mass properties), and the World holds
  // exactly it and the berm, as settings() reserved.
  const SampledMesh blade = scene().bladeShape();
  EXPECT_TRUE(blade.closed);
  EXPECT_TRUE(blade.warnings.empty());
  EXPECT_EQ(s_world->particleCount(),
            4 * kit::granuleCount(scene().config().berm) + blade.centres.size());
  EXPECT_EQ(s_world->particleCount(), s_world->particleCapacity());
  EXPECT_EQ(s_world->bodyCount(), s_world->bodyCapacity());

  std::size_t waiting = 0, pushing = 0, stopped = 0;
  for (const BladeSample& sample : s_path) {
    SCOPED_TRACE("step " + std::to_string(sample.step));
    const double done = static_cast<double>(std::clamp<std::int64_t>(
                            std::int64_t(sample.step - first), 0, std::int64_t(steps))) /
                        static_cast<double>(steps);
    // A frame's substeps add dt · v to x in float; 1e-6 m is about 60 roundings at x ~ 0.2 m.
    EXPECT_NEAR(sample.blade.position.x, start.x + travel * done, 1e-6);
    EXPECT_EQ(sample.blade.position.y, start.y);
    EXPECT_EQ(sample.blade.position.z, start.z);
    EXPECT_EQ(sample.blade.tiltDegrees, 0.0f);
    const bool moving = sample.step >= first && sample.step < first + steps;
    EXPECT_NEAR(sample.blade.speed, moving ? speed : 0.0, 1e-5);
    (sample.step < first ? waiting : moving ? pushing : stopped) += 1;
  }
  EXPECT_GT(waiting, 5u);
  EXPECT_GT(pushing, 5u);
  EXPECT_GT(stopped, 2u);
  const SceneBody end = scene().bodies(*s_world).at(0);
  EXPECT_FLOAT_EQ(end.position.x, start.x + static_cast<float>(travel));
}

// Before the push the blade stands still: the slumped berm leans on it (a mean force of 0.9 N
// over the wait, at most 1.4 N in a frame of the last 0.1 s, against μ M g = 41 N that would slide
// the whole berm) and in the last 0.1 s the sand barely moves: its centre of mass by 0.008 d, the
// median grain by 0.011 d (where the push moves the blade 2.5 d), a grain at the edge by 0.57 d.
// It never quite stops: the friction law, min(μ F_n, γ_s |v_s|), has no tangential spring, so a
// contact under shear creeps at the speed that makes γ_s |v_s| carry the load.
TEST_F(BulldozerRun, IdleBladeFeelsOnlyTheSandLeaningOnIt) {
  ASSERT_FALSE(s_still.empty());
  const double friction = scene().config().floorFriction * weight();
  const std::vector<Bulldozer::DragSample>& drag = scene().dragSeries();
  double largest = 0.0;
  std::size_t held = 0;
  for (std::size_t i = s_stillFromSample; i < drag.size(); ++i) {
    if (drag[i].phase != Phase::Waiting) break;
    // The sand pushes, it cannot pull (a small negative is damping as a grain settles).
    EXPECT_GT(drag[i].drag, -0.01 * friction) << "at " << drag[i].time << " s";
    largest = std::max(largest, std::abs(static_cast<double>(drag[i].drag)));
    ++held;
  }
  EXPECT_GE(held, 5u);
  std::printf("idle blade: largest drag %.3f N over the last %.1f s (mu M g %.1f N)\n", largest,
              kStillSeconds, friction);
  EXPECT_LT(largest, 0.1 * friction);
  const double shift = (comX(scene().atPushStart()) - comX(s_still)) / d();
  std::vector<double> moved;
  for (const BodyState& body : scene().atPushStart()) {
    if (!body.granule) continue;
    const BodyState& before = s_still.at(body.id.index);
    moved.push_back(std::hypot(body.position.x - before.position.x,
                               body.position.y - before.position.y,
                               body.position.z - before.position.z) /
                    d());
  }
  std::sort(moved.begin(), moved.end());
  const double median = moved[moved.size() / 2];
  std::printf(
      "last %.1f s before the push: centre of mass moved %.4f d, median granule %.5f d, "
      "farthest %.3f d\n",
      kStillSeconds, shift, median, moved.back());
  EXPECT_LT(std::abs(shift), 0.05);
  EXPECT_LT(median, 0.05);
}

// The drag is positive at every reading of the push, its mean (46 N, peak 64 N) at least the
// Coulomb friction of the sand that moves with the blade at the end (μ g · 7.3 kg = 36 N; the
// rest is the blade's downward push on the sand, 11 N on average, adding to the floor's load, and
// the sand it keeps gathering), and the floor's friction is nearly saturated:
// |ΔP_x - J_x| = 0.90 μ ∫F_y dt. Most of the berm slides on the floor as a block: that costs
// μ M g = 41 N, less than the passive failure of the sand in front of the blade would (Rankine,
// ½ K_p γ H² B = 70 N for K_p = 3, bulk weight γ = 15 kN/m³, height H = 4.5 d, width B = 19 d).
TEST_F(BulldozerRun, DragResistsThePushAsTheFloorFrictionOfTheSandItMoves) {
  std::size_t readings = 0;
  double peak = 0.0;
  for (const Bulldozer::DragSample& sample : scene().dragSeries()) {
    if (sample.phase != Phase::Pushing) continue;
    EXPECT_GT(sample.drag, 0.0f) << "at " << sample.time << " s";
    peak = std::max(peak, static_cast<double>(sample.drag));
    ++readings;
  }
  EXPECT_GE(readings, 40u);
  const Balance push = balance(Phase::Pushing, scene().atPushStart(), scene().atPushEnd());
  const double mean = push.bladeX / push.seconds;
  double carried = 0.0;  // kg
  for (const BodyState& body : scene().atPushEnd()) {
    if (body.granule && body.velocity.x > 0.5f * kBladeSpeed) carried += granuleMass();
  }
  const double mu = scene().config().floorFriction;
  std::printf(
      "push: mean drag %.2f N, peak %.2f N, carried %.2f kg (mu g m %.2f N), floor %.3f "
      "N s of mu * %.3f N s\n",
      mean, peak, carried, mu * kG * carried, push.floorX, push.normal);
  EXPECT_GT(carried, 0.5 * momentum(s_end, granuleMass()).mass);
  EXPECT_GE(mean, mu * kG * carried);
  EXPECT_GE(peak, mean);
  EXPECT_LT(push.floorX, 0.0) << "the floor must hold the sand back";
  EXPECT_GT(std::abs(push.floorX), 0.75 * mu * push.normal);

  const std::vector<SceneMetric> metrics = scene().metrics(s_end);
  auto metric = [&](std::string_view name) { return testing::metricNamed(metrics, name); };
  EXPECT_NEAR(metric("drag_mean_n"), mean, 1e-9 * mean);
  EXPECT_NEAR(metric("drag_peak_n"), peak, 1e-6 * peak);
  EXPECT_NEAR(metric("blade_travel_d"), kPushDistance, 1e-4);
}

// The Coulomb bound in the header holds in every phase: a force summed over the wrong substeps,
// with the wrong sign or not equal and opposite to the blade's on the sand would break it by tens
// of N s. Measured |ΔP_x - J_x| / (μ ∫F_y dt): 0.02 waiting, 0.90 pushing, 0.40 stopped.
TEST_F(BulldozerRun, BladeImpulseBalancesTheSandsMomentumAgainstTheFloor) {
  EXPECT_EQ(s_velocityClamps, 0u) << "the speed guard changed momenta";
  const double mu = scene().config().floorFriction;
  const struct {
    const char* name;
    Phase phase;
    const std::vector<BodyState>& from;
    const std::vector<BodyState>& to;
  } spans[] = {{"waiting", Phase::Waiting, s_start, scene().atPushStart()},
               {"pushing", Phase::Pushing, scene().atPushStart(), scene().atPushEnd()},
               {"stopped", Phase::Stopped, scene().atPushEnd(), s_end}};
  for (const auto& span : spans) {
    SCOPED_TRACE(span.name);
    const Balance b = balance(span.phase, span.from, span.to);
    std::printf("%s: %.3f s, blade on sand %.3f N s, floor %.3f N s, mu * normal %.3f N s\n",
                span.name, b.seconds, b.bladeX, b.floorX, mu * b.normal);
    // The floor's load over the span is the sand's weight to within what the blade holds up or
    // presses down (13% more while pushing) and the sand's vertical momentum change.
    EXPECT_NEAR(b.normal, weight() * b.seconds, 0.2 * weight() * b.seconds);
    // 2% for the float sums of forces over a frame's substeps on the GPU.
    EXPECT_LE(std::abs(b.floorX), 1.02 * mu * b.normal);
  }
}

// The blade moved 20 d into the berm; the sand's centre of mass moved 13.9 d of it, 137 of the 192
// grains end beyond the berm's front at the start of the push, and none behind the blade's face
// but those that spilled round its ends (none passes under or through the blade).
TEST_F(BulldozerRun, SandMovesAheadOfTheBlade) {
  const double shift = (comX(scene().atPushEnd()) - comX(scene().atPushStart())) / d();
  std::printf("sand's centre of mass moved %.2f d during the push\n", shift);
  EXPECT_GT(shift, 0.6 * kPushDistance);
  EXPECT_LT(shift, kPushDistance);
  const float face = scene().bladeFaceStart() + scene().bladeTravel();
  // The blade's ends: its particles' centres and their radius. A granule whose centre lies
  // within its bounding radius of an end reaches past it: it may have spilled round the end, and
  // once round it, it may roll back in behind the blade, by up to a diameter more.
  const float halfWidth =
      (0.5f * static_cast<float>(scene().config().berm[2] - 1) * kDefaultGranuleSpacing +
       scene().config().bladeOverhang + 0.5f) *
      d();
  const float shadow = halfWidth - tetrahedronTemplate(d(), 1.0f).boundingRadius - d();
  std::size_t behind = 0, ahead = 0, granules = 0;
  float front = -1e9f;
  for (const BodyState& body : scene().atPushStart()) {
    if (body.granule) front = std::max(front, body.position.x);
  }
  for (const BodyState& body : s_end) {
    if (!body.granule) continue;
    ++granules;
    if (body.position.x > front) ++ahead;
    if (body.position.x < face && std::abs(body.position.z) < shadow) ++behind;
  }
  std::printf("%zu of %zu granules beyond the berm's front, %zu behind the blade\n", ahead,
              granules, behind);
  EXPECT_EQ(behind, 0u);
  EXPECT_GT(ahead, granules / 2);
}

// Once the blade stops the sand slides on a little and the floor's friction takes its momentum;
// none is lost. Static friction lets the sand that leans on the blade stay there, pressing on it
// with a small part of the push's drag (a memoryless friction let it slump away). How much leans
// there follows the bits of the settling: 1.3% of the drag on Mesa 22.3, 2.7% on 25.0.
TEST_F(BulldozerRun, SandComesToRestAfterTheStop) {
  EXPECT_TRUE(scene().finished()) << scene().status();
  const std::vector<Bulldozer::DragSample>& drag = scene().dragSeries();
  ASSERT_FALSE(drag.empty());
  ASSERT_EQ(drag.back().phase, Phase::Stopped);
  const Balance push = balance(Phase::Pushing, scene().atPushStart(), scene().atPushEnd());
  EXPECT_LT(std::abs(drag.back().drag), 0.05 * push.bladeX / push.seconds);
  for (const BodyState& body : s_end) {
    if (body.granule) {
      EXPECT_TRUE(scene().contains(body.position)) << "granule " << body.id.index;
    }
  }
  const Momentum pushed = momentum(scene().atPushEnd(), granuleMass());
  const Momentum now = momentum(s_end, granuleMass());
  std::printf("sand's momentum along x: %.3f N s at the stop, %.4f N s at the end\n", pushed.x,
              now.x);
  EXPECT_GT(pushed.x, 0.5 * pushed.mass * kBladeSpeed);
  EXPECT_LT(std::abs(now.x), 0.02 * pushed.x);
}

}  // namespace
}  // namespace sandphys::scenes
