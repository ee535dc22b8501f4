// The viewer's Session on the headless context: what the panel switches at once, without the
// restart that material and time-step changes wait for.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <vector>

#include "scenes/registry.h"
#include "scenes/scene_parameters.h"
#include "support/test_world.h"
#include "viewer/session.h"

namespace sandphys::viewer {
namespace {

// Kernel profiling changes no bit of the result (Determinism.KernelProfilingChangesNoBit), so
// ticking it times the next frame's kernels in the same World, whose time goes on.
TEST(Session, KernelProfilingFollowsThePanelWithoutARestart) {
  std::unique_ptr<scenes::Scene> scene = scenes::createScene("box-drop");
  scenes::useTestSize(*scene);
  Session session(testing::gpu(), std::move(scene), 0.004);
  FrameStats stats;
  const samples::Ray noCursor{};
  session.stepFrame(false, false, noCursor, stats);
  const World* world = &session.world();
  const double time = world->simulatedTime();
  EXPECT_TRUE(world->kernelTimes().empty());

  session.controls().profileKernels = true;
  session.stepFrame(false, false, noCursor, stats);
  EXPECT_EQ(&session.world(), world) << "the World was rebuilt";
  EXPECT_GT(world->simulatedTime(), time) << "the run started over";
  EXPECT_FALSE(world->kernelTimes().empty());
  EXPECT_TRUE(session.applied().profileKernels);

  session.controls().profileKernels = false;
  session.stepFrame(false, false, noCursor, stats);
  EXPECT_TRUE(world->kernelTimes().empty());
}

// Pushing brings the tool's sphere into the World and, with it, its surface: a metal ball whose
// outline holds every particle of the sphere (they are half a diameter inside it).
TEST(Session, ThePushingSphereIsDrawnAsAMetalBallAroundItsParticles) {
  std::unique_ptr<scenes::Scene> scene = scenes::createScene("box-drop");
  scenes::useTestSize(*scene);
  Session session(testing::gpu(), std::move(scene), 0.004);
  FrameStats stats;
  EXPECT_EQ(session.tools().surface(), nullptr);
  // Straight down onto the middle of the scene's floor.
  const scenes::SceneBounds bounds = session.scene().bounds();
  samples::Ray down;
  down.origin = {0.5f * (bounds.min.x + bounds.max.x), bounds.max.y + 1.0f,
                 0.5f * (bounds.min.z + bounds.max.z)};
  down.direction = {0.0f, -1.0f, 0.0f};
  session.stepFrame(false, true, down, stats);
  const scenes::SceneSurface* ball = session.tools().surface();
  ASSERT_NE(ball, nullptr);
  EXPECT_EQ(ball->material, scenes::BodyMaterial::Metal);
  const float d = session.world().settings().particleDiameter;
  float outline = 0.0f;
  for (const Vec3& v : ball->mesh.vertices) outline = std::max(outline, length(v));
  EXPECT_NEAR(outline, (SandTools::kSphereRadius + 0.5f) * d, 1e-4f);
  const std::vector<BodyState> bodies = session.world().readBodies();
  const Vec3 centre = bodies[ball->body.index].position;
  int particles = 0;
  for (const ParticleState& p : session.world().readParticles()) {
    if (!(p.body == ball->body)) continue;
    ++particles;
    EXPECT_LE(length(p.position - centre) + 0.5f * d, outline + 1e-4f);
  }
  EXPECT_GT(particles, 100);
}

}  // namespace
}  // namespace sandphys::viewer
