// The scene registry, scene parameters and the capacities scenes ask for (CPU only).
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>
#include <vector>

#include "scenes/box_drop.h"
#include "scenes/cylinder_pile.h"
#include "scenes/registry.h"
#include "scenes/scene_parameters.h"

namespace sandphys::scenes {
namespace {

TEST(SceneRegistry, EveryEntryIsUniqueAndMakesItsScene) {
  std::set<std::string_view> names;
  ASSERT_FALSE(sceneRegistry().empty());
  for (const SceneEntry& entry : sceneRegistry()) {
    EXPECT_TRUE(names.insert(entry.name).second) << "duplicate scene " << entry.name;
    EXPECT_FALSE(entry.category.empty()) << entry.name;
    EXPECT_EQ(findScene(entry.name), &entry);
    std::unique_ptr<Scene> scene = createScene(entry.name);
    ASSERT_NE(scene, nullptr);
    EXPECT_EQ(scene->name(), entry.name);
    const WorldSettings settings = scene->settings();
    EXPECT_GT(settings.maxBodies, 0u) << entry.name;
    EXPECT_GE(settings.maxParticles, settings.maxBodies) << entry.name;
    const SceneBounds bounds = scene->bounds();
    EXPECT_LT(bounds.min.x, bounds.max.x) << entry.name;
    EXPECT_LT(bounds.min.y, bounds.max.y) << entry.name;
    EXPECT_LT(bounds.min.z, bounds.max.z) << entry.name;
  }
  EXPECT_NE(findScene("cylinder-pile"), nullptr);
}

TEST(SceneRegistry, UnknownNameIsRefusedWithTheKnownNames) {
  EXPECT_EQ(findScene("no-such-scene"), nullptr);
  try {
    createScene("no-such-scene");
    FAIL() << "createScene accepted an unknown name";
  } catch (const InvalidArgument& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("no-such-scene"), std::string::npos) << message;
    EXPECT_NE(message.find("cylinder-pile"), std::string::npos) << message;
  }
}

TEST(CylinderPile, DefaultsAreThePapersBenchmark) {
  const CylinderPile pile;
  EXPECT_EQ(pile.batchGranules(), 32u * 32u * 16u);  // 16,384 granules per batch
  EXPECT_EQ(pile.config().batch[1], 16u);            // 16 layers high
  EXPECT_FLOAT_EQ(pile.config().cylinderRadius, 50.0f);
  EXPECT_FLOAT_EQ(pile.config().cylinderHeight, 100.0f);
  EXPECT_FLOAT_EQ(pile.config().firstDropHeight, 50.0f);
  EXPECT_FLOAT_EQ(pile.config().dropGap, 15.0f);
  EXPECT_FLOAT_EQ(pile.config().particleDiameter, 0.02f);
}

TEST(CylinderPile, CapacityHoldsEveryBatchAndTheFloor) {
  CylinderPile pile;
  pile.config().batches = 4;
  pile.config().batch = {8, 4, 8};
  const WorldSettings settings = pile.settings();
  EXPECT_EQ(settings.maxBodies, 4u * 256u + 1u);
  EXPECT_EQ(settings.maxParticles, 4u * 4u * 256u + 7845u);
  EXPECT_FLOAT_EQ(settings.particleDiameter, 0.02f);

  CylinderPile paper;
  EXPECT_EQ(paper.settings().maxBodies, 16384u + 1u);
  EXPECT_EQ(paper.settings().maxParticles, 4u * 16384u + 7845u);
}

TEST(CylinderPile, PaperBatchFitsInsideTheWall) {
  // 1024 columns at 2.4 d form a disc of radius ~43 d; a 32 × 32 square would reach 52.6 d.
  const CylinderPile pile;
  EXPECT_GT(pile.batchReach(), 40.0f * 0.02f);
  EXPECT_LT(pile.batchReach(), 50.0f * 0.02f);

  CylinderPile wide;
  wide.config().batch = {40, 4, 40};
  EXPECT_GT(wide.batchReach(), 50.0f * 0.02f);
  try {
    (void)wide.settings();
    FAIL() << "a batch wider than the cylinder was accepted";
  } catch (const InvalidArgument& error) {
    EXPECT_NE(std::string(error.what()).find("outside the cylinder"), std::string::npos)
        << error.what();
  }
}

TEST(CylinderPile, TooManyGranulesAreRefused) {
  CylinderPile pile;
  pile.config().batches = 4096;
  pile.config().batch = {1024, 1024, 1024};
  EXPECT_THROW((void)pile.settings(), InvalidArgument);
}

TEST(CylinderPile, ContainerIsTheCylinderAboveTheFloor) {
  const CylinderPile pile;
  EXPECT_TRUE(pile.contains({0.0f, 0.5f, 0.0f}));
  EXPECT_TRUE(pile.contains({0.99f, 0.1f, 0.0f}));
  EXPECT_FALSE(pile.contains({1.01f, 0.1f, 0.0f}));  // outside the wall (r = 50 d = 1 m)
  EXPECT_FALSE(pile.contains({0.8f, 0.1f, 0.8f}));
  EXPECT_FALSE(pile.contains({0.0f, -0.01f, 0.0f}));  // under the floor
}

TEST(CylinderPile, PileTopIsARobustHighPointOfTheContainedGranules) {
  const CylinderPile pile;  // not built: the granule radius is not added
  std::vector<BodyState> bodies;
  for (int i = 0; i < 200; ++i) {
    bodies.push_back({.id = {.index = static_cast<std::uint32_t>(i)},
                      .position = {0.0f, 0.001f * static_cast<float>(i), 0.0f}});
  }
  BodyState floor{.id = {.index = 200}, .position = {0.0f, 5.0f, 0.0f}};
  floor.granule = false;
  bodies.push_back(floor);  // not a granule: ignored
  bodies.push_back({.id = {.index = 201}, .position = {3.0f, 9.0f, 0.0f}});  // outside: ignored
  BodyState dead{.id = {.index = 202}, .position = {0.0f, 8.0f, 0.0f}};
  dead.alive = false;
  bodies.push_back(dead);
  BodyState bouncer{.id = {.index = 203}, .position = {0.0f, 3.0f, 0.0f}};  // one outlier: ignored
  bodies.push_back(bouncer);
  const float top = pile.pileTop(bodies);
  EXPECT_GT(top, 0.190f);
  EXPECT_LT(top, 0.2f);
  EXPECT_EQ(pile.pileTop({}), 0.0f);
}

TEST(SceneParameters, SetFromTextWithinTheRange) {
  CylinderPile pile;
  setSceneParameter(pile, "batch", "8,4,8");
  EXPECT_EQ(pile.config().batch, (Count3{8, 4, 8}));
  setSceneParameter(pile, "batch", "2 3 5");
  EXPECT_EQ(pile.config().batch, (Count3{2, 3, 5}));
  setSceneParameter(pile, "batches", "3");
  EXPECT_EQ(pile.config().batches, 3u);
  setSceneParameter(pile, "seed", "18446744073709551615");
  EXPECT_EQ(pile.config().seed, 18446744073709551615ull);
  setSceneParameter(pile, "settle-speed", "0.125");
  EXPECT_FLOAT_EQ(pile.config().settleSpeed, 0.125f);

  const std::vector<SceneParameter> parameters = pile.parameters();
  const auto batch = std::find_if(parameters.begin(), parameters.end(),
                                  [](const SceneParameter& p) { return p.name == "batch"; });
  ASSERT_NE(batch, parameters.end()) << "the cylinder pile has no parameter 'batch'";
  EXPECT_EQ(formatSceneParameter(*batch), "2,3,5");
}

TEST(SceneParameters, BadTextIsRefusedNamingParameterAndValue) {
  CylinderPile pile;
  const CylinderPile::Config before = pile.config();
  const char* cases[][2] = {{"batches", "-1"},    {"batches", "0"},        {"batches", "two"},
                            {"batches", "3x"},    {"batch", "8,4"},        {"batch", "8,0,8"},
                            {"batch", "8,4,8,1"}, {"settle-speed", "nan"}, {"diameter", "-0.02"}};
  for (const auto& [name, value] : cases) {
    try {
      setSceneParameter(pile, name, value);
      ADD_FAILURE() << name << " = " << value << " was accepted";
    } catch (const InvalidArgument& error) {
      const std::string message = error.what();
      EXPECT_NE(message.find(name), std::string::npos) << message;
      EXPECT_NE(message.find(value), std::string::npos) << message;
    }
  }
  EXPECT_EQ(pile.config().batches, before.batches);
  EXPECT_EQ(pile.config().batch, before.batch);

  try {
    setSceneParameter(pile, "no-such-knob", "1");
    ADD_FAILURE() << "unknown parameter accepted";
  } catch (const InvalidArgument& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("no-such-knob"), std::string::npos) << message;
    EXPECT_NE(message.find("batches"), std::string::npos) << message;  // lists what exists
  }
}

TEST(BoxDrop, CapacityIsTheBlock) {
  BoxDrop box;
  setSceneParameter(box, "block", "4,5,6");
  EXPECT_EQ(box.settings().maxBodies, 120u);
  EXPECT_EQ(box.settings().maxParticles, 480u);
  EXPECT_TRUE(box.contains({0.0f, 0.1f, 0.0f}));
  EXPECT_FALSE(box.contains({0.3f, 0.1f, 0.0f}));
}

}  // namespace
}  // namespace sandphys::scenes
