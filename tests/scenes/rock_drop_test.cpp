// The rock-drop scene with a small bed: the default rock (assets/rock.obj at 0.14 m, 7 d long,
// 708 particles) dropped 8 d onto a settled bed of 8 x 4 x 8 = 256 granules. It comes to rest on
// the sand, sunk into it: granules under it (not on the box floor), below the bed's top, and none
// inside it, and stays there: it sinks by less than 0.01 d in the second after it stopped. Without
// contacts with the sand it would fall through to the floor, and the "granules under it" bound
// would fail.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include "scenes/rock_drop.h"
#include "support/scene_metric.h"
#include "support/test_world.h"

namespace sandphys::scenes {
namespace {

constexpr float kFrame = 1.0f / 60.0f;

// Winding number of a closed, outward-wound mesh about `p`: 1 inside, 0 outside. The sum of
// the solid angles of its triangles seen from p (Van Oosterom & Strackee 1983), over 4π.
double windingNumber(const TriangleMesh& mesh, const Vec3& p) {
  double total = 0.0;
  for (const auto& triangle : mesh.triangles) {
    double r[3][3];
    double len[3];
    for (int k = 0; k < 3; ++k) {
      const Vec3& v = mesh.vertices[triangle[k]];
      r[k][0] = double(v.x) - p.x;
      r[k][1] = double(v.y) - p.y;
      r[k][2] = double(v.z) - p.z;
      len[k] = std::sqrt(r[k][0] * r[k][0] + r[k][1] * r[k][1] + r[k][2] * r[k][2]);
    }
    const auto dot = [](const double* a, const double* b) {
      return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    };
    const double det = r[0][0] * (r[1][1] * r[2][2] - r[1][2] * r[2][1]) -
                       r[0][1] * (r[1][0] * r[2][2] - r[1][2] * r[2][0]) +
                       r[0][2] * (r[1][0] * r[2][1] - r[1][1] * r[2][0]);
    const double denominator = len[0] * len[1] * len[2] + dot(r[0], r[1]) * len[2] +
                               dot(r[1], r[2]) * len[0] + dot(r[2], r[0]) * len[1];
    total += 2.0 * std::atan2(det, denominator);
  }
  return total / (4.0 * std::numbers::pi);
}

// The metric called `name` of `scene` for `bodies`; one the scene does not report fails the test.
double metric(const RockDrop& scene, std::span<const BodyState> bodies, std::string_view name) {
  return testing::metricNamed(scene.metrics(bodies), name);
}

// fit scales the mesh to a largest extent of that many metres, and a rock wider than the bed
// grows the bed (along x and z only) until the box holds the rock as it is let go.
TEST(RockDrop, FitSizesTheRockAndTheBedGrowsToHoldIt) {
  RockDrop fitted;
  fitted.config().fit = 0.3f;
  Vec3 lo{1e9f, 1e9f, 1e9f}, hi{-1e9f, -1e9f, -1e9f};
  for (const Vec3& v : fitted.rockMesh().vertices) {
    lo = {std::min(lo.x, v.x), std::min(lo.y, v.y), std::min(lo.z, v.z)};
    hi = {std::max(hi.x, v.x), std::max(hi.y, v.y), std::max(hi.z, v.z)};
  }
  EXPECT_NEAR(std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z}), 0.3f, 1e-6f);

  RockDrop wide;
  wide.config().scale = 1.0f;  // 1 m across: the default 12 x 12 bed is 0.6 m wide
  const Count3 bed = wide.bedCounts();
  EXPECT_GT(bed[0], 12u);
  EXPECT_GT(bed[2], 12u);
  EXPECT_EQ(bed[1], wide.config().bed[1]);
  EXPECT_EQ(wide.settings().maxBodies, bed[0] * bed[1] * bed[2] + 1u);
  // The box is at least as wide as the rock (1 m along its longest axis, turned as it is let
  // go: at least half of that on each side of its centre along x or z).
  const SceneBounds box = wide.bounds();
  EXPECT_GT(std::max(box.max.x, box.max.z), 0.5f);
  // The default rock fits the default bed, which stays as it was.
  EXPECT_EQ(RockDrop{}.bedCounts(), (Count3{12, 5, 12}));
}

TEST(RockDrop, RockSinksIntoTheBedAndComesToRestOnSand) {
  RockDrop scene;
  scene.config().bed = {8, 4, 8};
  const float d = scene.config().particleDiameter;
  // The asset is a closed surface, so the rock is a solid (filled, with a solid's mass).
  const MeshEdges edges = analyseEdges(scene.rockMesh());
  EXPECT_TRUE(edges.closed()) << edges.openEdges << " open, " << edges.misorientedEdges
                              << " misoriented edges of " << edges.edges;
  World world(testing::gpu(), scene.settings());
  scene.build(world);
  ASSERT_EQ(world.granulesSpawned(), 256u);

  // The bed settles (0.4 to 0.5 s), the rock falls 8 d (0.13 s) and comes to rest; 6 s is far
  // more.
  int frame = 0;
  while (!scene.finished() && world.simulatedTime() < 6.0) {
    const StepReport report = scene.step(world, kFrame);
    scene.update(world, report, world.simulatedTime());
    if (++frame % 12 == 0 && scene.dropped()) {
      const std::vector<BodyState> bodies = world.readBodies();
      std::printf("t %.2f s (%s): rock lowest point %.4f m, bed top %.4f m, speed %.4f m/s\n",
                  world.simulatedTime(), scene.status().c_str(),
                  metric(scene, bodies, "rock_lowest_m"), metric(scene, bodies, "bed_top_m"),
                  metric(scene, bodies, "rock_speed_m_per_s"));
    }
  }
  ASSERT_TRUE(scene.dropped()) << "the rock was never dropped: " << scene.status();
  ASSERT_TRUE(scene.finished()) << "the rock did not stop within 6 s: " << scene.status();
  const double restedAt = world.simulatedTime();

  // A further second: at rest means it stays where it is.
  const BodyState before = world.readBody(scene.rock());
  while (world.simulatedTime() < restedAt + 1.0) {
    const StepReport report = scene.step(world, kFrame);
    scene.update(world, report, world.simulatedTime());
  }
  const BodyState rock = world.readBody(scene.rock());
  const float speed = std::hypot(rock.velocity.x, rock.velocity.y, rock.velocity.z);
  const float heightChange = std::abs(rock.position.y - before.position.y);
  const std::vector<BodyState> bodies = world.readBodies();
  const auto lowest = static_cast<float>(metric(scene, bodies, "rock_lowest_m"));
  const auto depth = static_cast<float>(metric(scene, bodies, "rock_rest_depth_m"));
  const auto bedTop = static_cast<float>(metric(scene, bodies, "bed_top_m"));

  // The surface is the rock's mesh about its centre of mass, in the frame its orientation turns.
  const TriangleMesh& surface = scene.surfaces()[0].mesh;
  std::uint32_t inside = 0;
  for (const BodyState& body : bodies) {
    if (!body.granule) continue;
    const Vec3 p = rotate(conjugate(rock.orientation), body.position - rock.position);
    if (windingNumber(surface, p) > 0.5) ++inside;
  }
  std::printf(
      "rock: %u particles, at rest %.2f s after the drop, speed %.4f m/s, height change over "
      "the next second %.2e m; lowest point %.4f m (%.2f d) above the floor, %.4f m (%.2f d) below "
      "the "
      "bed's top %.4f m; %u granule centres inside it\n",
      world.particleCount() - 4 * world.granulesSpawned(), restedAt - scene.droppedAt(), speed,
      heightChange, lowest, lowest / d, depth, depth / d, bedTop, inside);

  // At rest: slower than the scene's rest speed (0.01 m/s), and sinking by less than a hundredth
  // of a grain in the second after it stopped (static friction holds the bed: under the paper's
  // memoryless friction the rock crept down at about a tenth of a grain per second).
  EXPECT_LT(speed, 0.01f) << "m/s";
  EXPECT_LT(heightChange, 0.01f * d) << "m over the second after it stopped";
  // On the sand: on the bare floor its lowest vertex would be one particle radius (0.5 d) above
  // it; a grain between them lifts it to at least 1.5 d.
  EXPECT_GT(lowest, 1.0f * d) << "the rock's lowest point is on the box floor (m)";
  // In the sand: its lowest point is below the bed's top (the median top of the particles away
  // from the walls; 4 layers settle to about 3.4 d). The impact pushes the top grains aside; once
  // it rests, static friction holds the bed, so it sinks no further (under the paper's memoryless
  // friction it crept on into the bed).
  EXPECT_GT(depth, 0.05f * d) << "the rock did not sink into the bed (m below the top)";
  EXPECT_EQ(inside, 0u) << "granule centres inside the rock";
  for (const BodyState& body : bodies) {
    if (!body.granule) continue;
    EXPECT_TRUE(scene.contains(body.position)) << "granule " << body.id.index;
  }
}

}  // namespace
}  // namespace sandphys::scenes
