// The viewer's Session on the headless context: what the panel switches at once, without the
// restart that material and time-step changes wait for.
#include <gtest/gtest.h>

#include <memory>

#include "scenes/registry.h"
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
  const scenes::Ray noCursor{};
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

}  // namespace
}  // namespace sandphys::viewer
