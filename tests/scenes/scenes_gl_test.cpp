// Every registered scene, a test of its own (EveryScene/RegisteredScene.*/<scene>), so that one
// scene's failure hides no other's: it builds in a World made from its own settings, starts with
// its granules inside its container (or pours them in: the scenes with emitters start empty) and
// survives a few substeps and an update.
#include <gtest/gtest.h>

#include "scenes/registry.h"
#include "scenes/scene_parameters.h"
#include "support/every_scene.h"

namespace sandphys::scenes {
namespace {

class RegisteredScene : public ::testing::TestWithParam<const SceneEntry*> {};

TEST_P(RegisteredScene, BuildsInsideItsContainerAndSteps) {
  const GpuContext gpu = GpuContext::headless();
  std::unique_ptr<Scene> scene = GetParam()->create();
  useTestSize(*scene);
  World world(gpu, scene->settings());
  scene->build(world);
  std::uint32_t granules = 0;
  for (const BodyState& body : world.readBodies()) {
    if (!body.granule) continue;
    ++granules;
    EXPECT_TRUE(scene->contains(body.position)) << "granule " << body.id.index << " starts outside";
  }

  // A frame, or as many as a pouring scene takes to emit its first layer (at most 0.1 s).
  std::uint32_t emitted = 0;
  for (int frame = 0; frame == 0 || (granules + emitted == 0 && frame < 60); ++frame) {
    const StepReport report = scene->step(world, 1.0f / 600.0f);
    EXPECT_GT(report.substeps, 0u);
    scene->update(world, report, world.simulatedTime());
    emitted += report.granulesEmitted;
  }
  EXPECT_GT(granules + emitted, 0u) << "no sand at all";
  const WorldStats stats = world.readStats();
  EXPECT_EQ(stats.granulesAlive, granules + emitted);
  // Nothing starts inside anything: the first frame's deepest contact is a fresh impact's, far
  // below the overlap of two touching grains pressed together by a whole scene's weight.
  EXPECT_LT(stats.maxOverlap, 0.05 * world.settings().particleDiameter)
      << "granules start overlapping";
}

INSTANTIATE_TEST_SUITE_P(EveryScene, RegisteredScene,
                         ::testing::ValuesIn(testing::registeredScenes()), testing::sceneTestName);

}  // namespace
}  // namespace sandphys::scenes
