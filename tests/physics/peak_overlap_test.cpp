// WorldStats::maxOverlap is the peak since the last step() or resetPeakOverlap(): reading it
// changes nothing, a reset restarts it, and a resting contact raises it again at once.
#include <gtest/gtest.h>

#include "support/test_world.h"

namespace sandphys {
namespace {

TEST(PeakOverlap, ReadingKeepsItAndAResetRestartsIt) {
  testing::TestWorld w;
  w.addFloor();
  const float d = w->settings().particleDiameter;
  w.addGranule({0.0f, 2.0f * d, 0.0f});
  w.simulate(1.0);  // drops about a diameter and comes to rest on the floor

  const double peak = w->readStats().maxOverlap;
  EXPECT_GT(peak, 0.0);
  EXPECT_LT(peak, 0.1 * d);
  EXPECT_EQ(w->readStats().maxOverlap, peak) << "a second read changed the peak";

  w->resetPeakOverlap();
  EXPECT_EQ(w->readStats().maxOverlap, 0.0);
  w->substep(1);
  const double resting = w->readStats().maxOverlap;
  EXPECT_GT(resting, 0.0) << "the resting contact raises the peak again";
  EXPECT_LE(resting, peak) << "a granule at rest overlaps less than when it landed";

  // step() starts each frame's peak afresh: a frame at rest peaks where the granule rests.
  const StepReport frame = w->step(1.0f / 60.0f);
  ASSERT_TRUE(frame.hasStats || !w->settings().statsEachFrame);
  EXPECT_NEAR(w->readStats().maxOverlap, resting, 0.01 * resting);
}

}  // namespace
}  // namespace sandphys
