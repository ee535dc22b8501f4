// The headless context and the adoption of a current one.
#include <gtest/gtest.h>

#include "support/test_world.h"

namespace sandphys {
namespace {

TEST(GpuContext, HeadlessOffersOpenGl45) {
  const GpuContext& gpu = testing::gpu();
  EXPECT_TRUE(gpu.isHeadless());
  EXPECT_NE(gpu.description().find("4.5"), std::string::npos) << gpu.description();
}

TEST(GpuContext, AdoptsTheContextCurrentOnThisThread) {
  testing::gpu().makeCurrent();
  GpuContext adopted = GpuContext::fromCurrentContext();
  EXPECT_FALSE(adopted.isHeadless());
  // A world on the adopted context runs like any other.
  World world(adopted, testing::smallSettings());
  world.addGranules(GranuleBlock{.center = {0, 1, 0}, .countX = 2, .countY = 1, .countZ = 1});
  world.substep(10);
  EXPECT_LT(world.readBodies()[0].velocity.y, 0.0f);
}

}  // namespace
}  // namespace sandphys
