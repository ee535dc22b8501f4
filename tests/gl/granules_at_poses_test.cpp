// World::addGranules(span of BodyDesc): granules where the caller puts them, with typed ids that
// read back the same poses; a bad desc or too many granules add nothing and name the problem.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "support/test_world.h"

namespace sandphys {
namespace {

using testing::errorMessageOf;

std::vector<BodyDesc> threePoses() {
  return {
      {.position = {0.1f, 0.3f, -0.05f}},
      {.position = {-0.2f, 0.5f, 0.0f},
       .orientation = fromAxisAngle({0, 1, 0}, 0.6f),
       .velocity = {0.0f, -1.0f, 0.25f}},
      {.position = {0.0f, 0.8f, 0.2f},
       .orientation = fromAxisAngle(normalized({1, 1, 0}), -1.1f),
       .angularVelocity = {0.0f, 3.0f, 0.0f}},
  };
}

TEST(GranulesAtPoses, ReadBackWhereTheyWerePutWithTheirIds) {
  testing::TestWorld w;
  w->addGranules(GranuleBlock{.center = {0, 1, 0}, .countX = 2, .countY = 1, .countZ = 1});
  const std::vector<BodyDesc> poses = threePoses();
  const std::vector<BodyId> ids = w->addGranules(poses);
  ASSERT_EQ(ids.size(), 3u);
  EXPECT_EQ(w->bodyCount(), 5u);
  EXPECT_EQ(w->particleCount(), 20u);
  for (std::size_t i = 0; i < ids.size(); ++i) {
    EXPECT_EQ(ids[i].index, 2u + i);
    const BodyState s = w->readBody(ids[i]);
    EXPECT_TRUE(s.granule && s.alive);
    EXPECT_NEAR(s.position.x, poses[i].position.x, 1e-6f);
    EXPECT_NEAR(s.position.y, poses[i].position.y, 1e-6f);
    EXPECT_NEAR(s.position.z, poses[i].position.z, 1e-6f);
    // The same rotation (q and -q are one): the orientation turns a vector as the pose did.
    const Vec3 probe{0.3f, -0.7f, 0.5f};
    const Vec3 turned = rotate(s.orientation, probe);
    const Vec3 expected = rotate(poses[i].orientation, probe);
    EXPECT_NEAR(length(turned - expected), 0.0f, 1e-5f) << "granule " << i;
    EXPECT_NEAR(length(s.velocity - poses[i].velocity), 0.0f, 1e-6f);
    EXPECT_NEAR(length(s.angularVelocity - poses[i].angularVelocity), 0.0f, 1e-5f);
  }
}

TEST(GranulesAtPoses, ABadDescOrTooManyGranulesAddNothingAndNameIt) {
  testing::TestWorld w(testing::smallSettings(4));
  std::vector<BodyDesc> poses = threePoses();
  poses[1].velocity.y = std::numeric_limits<float>::quiet_NaN();
  std::string message = errorMessageOf([&] { w->addGranules(poses); });
  EXPECT_NE(message.find("granules[1].velocity"), std::string::npos) << message;
  poses = threePoses();
  poses[2].orientation = {0, 0, 0, 0};
  message = errorMessageOf([&] { w->addGranules(poses); });
  EXPECT_NE(message.find("granules[2].orientation"), std::string::npos) << message;
  poses = threePoses();
  poses[0].motion = Motion::Kinematic;
  message = errorMessageOf([&] { w->addGranules(poses); });
  EXPECT_NE(message.find("granules[0].motion"), std::string::npos) << message;
  EXPECT_EQ(w->bodyCount(), 0u);

  poses = threePoses();
  poses.push_back({.position = {0.3f, 0.3f, 0.3f}});
  poses.push_back({.position = {-0.3f, 0.3f, 0.3f}});
  message = errorMessageOf([&] { w->addGranules(poses); });
  EXPECT_NE(message.find("WorldSettings.maxBodies = 4"), std::string::npos) << message;
  EXPECT_EQ(w->bodyCount(), 0u);
  EXPECT_EQ(w->particleCount(), 0u);
  EXPECT_TRUE(w->addGranules(std::span<const BodyDesc>{}).empty());
}

}  // namespace
}  // namespace sandphys
