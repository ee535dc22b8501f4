// The viewer's pieces that need no window: key scripts, camera control, tool capacities, plots.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "viewer/camera_control.h"
#include "viewer/frame_stats.h"
#include "viewer/input.h"
#include "viewer/sand_tools.h"

namespace sandphys::viewer {
namespace {

TEST(KeyScript, AcceptsPressesAndHolds) {
  EXPECT_TRUE(KeyScript::parse("").empty());
  EXPECT_FALSE(KeyScript::parse("F@5").empty());
  EXPECT_FALSE(KeyScript::parse("P@2-9,b@3,ESC@12,SPACE@0,7@1").empty());
}

TEST(KeyScript, RefusesBadEntriesNamingThem) {
  for (const char* bad : {"F", "F@", "F@x", "F@5-2", "WHAT@3", "F@-1"}) {
    try {
      (void)KeyScript::parse(bad);
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const std::runtime_error& error) {
      EXPECT_NE(std::string(error.what()).find("SANDPHYS_VIEWER_KEYS"), std::string::npos);
      EXPECT_NE(std::string(error.what()).find(bad), std::string::npos) << error.what();
    }
  }
}

TEST(CameraControl, RayThroughTheCentreHitsTheTarget) {
  render::Camera camera;
  camera.target = {0.3f, 0.1f, -0.2f};
  camera.distance = 2.0f;
  const Ray ray = camera_control::rayThrough(camera, 400.0f, 300.0f, 800.0f, 600.0f);
  const Eigen::Vector3f toTarget = camera.target - ray.origin;
  // Distance of the target from the ray, m: the centre pixel looks straight at it.
  EXPECT_LT((toTarget - toTarget.dot(ray.direction) * ray.direction).norm(), 1e-5f);
  const std::optional<Eigen::Vector3f> hit = hitHorizontalPlane(ray, camera.target.y());
  ASSERT_TRUE(hit.has_value());
  EXPECT_LT((*hit - camera.target).norm(), 1e-4f);
}

TEST(CameraControl, CornerRaysSpanTheFieldOfView) {
  render::Camera camera;
  const Ray top = camera_control::rayThrough(camera, 400.0f, 0.0f, 800.0f, 600.0f);
  const Ray bottom = camera_control::rayThrough(camera, 400.0f, 600.0f, 800.0f, 600.0f);
  EXPECT_NEAR(std::acos(top.direction.dot(bottom.direction)), camera.fovY, 1e-4f);
  EXPECT_GT(top.direction.y(), bottom.direction.y());  // window y grows downwards
}

TEST(CameraControl, NoHitWhenLookingAwayFromThePlane) {
  const Ray up{{0.0f, 1.0f, 0.0f}, {0.0f, 1.0f, 0.0f}};
  EXPECT_FALSE(hitHorizontalPlane(up, 0.0f).has_value());
  const Ray level{{0.0f, 1.0f, 0.0f}, {1.0f, 0.0f, 0.0f}};
  EXPECT_FALSE(hitHorizontalPlane(level, 0.0f).has_value());
}

TEST(CameraControl, OrbitKeepsThePitchOffThePoles) {
  render::Camera camera;
  camera_control::orbit(camera, 0.0f, 1.0e5f);
  EXPECT_FLOAT_EQ(camera.pitch, camera_control::kMaxPitch);
  camera_control::orbit(camera, 0.0f, -1.0e5f);
  EXPECT_FLOAT_EQ(camera.pitch, -camera_control::kMaxPitch);
}

TEST(CameraControl, PanMovesTheTargetAcrossTheView) {
  render::Camera camera;
  const Eigen::Vector3f before = camera.target;
  const Eigen::Vector3f forward = (camera.target - camera.eye()).normalized();
  camera_control::pan(camera, 50.0f, -20.0f, 600.0f);
  const Eigen::Vector3f moved = camera.target - before;
  EXPECT_GT(moved.norm(), 0.0f);
  EXPECT_NEAR(moved.dot(forward), 0.0f, 1e-5f);  // in the image plane, no zoom
  // A drag of the window's full height moves the scene by the view's height at the target.
  render::Camera tall;
  const Eigen::Vector3f start = tall.target;
  camera_control::pan(tall, 0.0f, 600.0f, 600.0f);
  EXPECT_NEAR((tall.target - start).norm(), 2.0f * tall.distance * std::tan(0.5f * tall.fovY),
              1e-4f);
}

TEST(CameraControl, ZoomIsGeometricAndBounded) {
  render::Camera camera;
  camera.distance = 2.0f;
  camera_control::zoom(camera, 1.0f);
  const float once = camera.distance;
  EXPECT_LT(once, 2.0f);
  camera_control::zoom(camera, -1.0f);
  EXPECT_NEAR(camera.distance, 2.0f, 1e-5f);
  camera_control::zoom(camera, 1.0e4f);
  EXPECT_FLOAT_EQ(camera.distance, camera_control::kMinDistance);
}

TEST(SandTools, CapacityCoversThePourBudgetAndTheSphere) {
  WorldSettings granulesOnly;
  granulesOnly.maxBodies = 100;  // maxParticles 0: four per body
  const WorldSettings grown = SandTools::withToolCapacity(granulesOnly);
  EXPECT_EQ(grown.maxBodies, 100u + SandTools::kPourGranules + 1u);
  // Ball of radius 6 d on a lattice of spacing d: about 4/3 π 6³ ≈ 905 particles.
  EXPECT_GT(grown.maxParticles, 400u + 4u * SandTools::kPourGranules + 800u);
  EXPECT_LT(grown.maxParticles, 400u + 4u * SandTools::kPourGranules + 1000u);

  WorldSettings withFloor;
  withFloor.maxBodies = 101;
  withFloor.maxParticles = 5000;  // a rough floor's particles on top of the granules
  EXPECT_GT(SandTools::withToolCapacity(withFloor).maxParticles,
            5000u + 4u * SandTools::kPourGranules);
}

TEST(PlotHistory, KeepsTheNewestValuesInOrder) {
  PlotHistory history;
  for (int i = 0; i < static_cast<int>(PlotHistory::kLength) + 10; ++i) {
    history.push(static_cast<float>(i));
  }
  ASSERT_EQ(history.size(), static_cast<int>(PlotHistory::kLength));
  EXPECT_FLOAT_EQ(history.data()[0], 10.0f);
  EXPECT_FLOAT_EQ(history.latest(), static_cast<float>(PlotHistory::kLength + 9));
  EXPECT_FLOAT_EQ(history.max(), history.latest());
}

}  // namespace
}  // namespace sandphys::viewer
