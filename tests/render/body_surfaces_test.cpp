// Bodies drawn as what they are (Scene::surfaces): each scene that has bodies, at its test size,
// seen from its own view as the viewer opens it with the panel shown (Camera::framing clear of
// the panel's strip). A body's pixels are those that change when its surface alone is left out
// (its particles stay hidden), drawn without shadows or ambient occlusion so that nothing else
// changes. Each body must show beside the panel's place, in its material's colour rather than
// the sand's; RenderSettings::bodyParticles brings its particles back.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "render/camera.h"
#include "render/offscreen_target.h"
#include "render/renderer.h"
#include "scenes/registry.h"
#include "scenes/scene_parameters.h"
#include "support/test_world.h"

namespace sandphys::testing {
namespace {

constexpr int kWidth = 640;
constexpr int kHeight = 400;
// The viewer's panel at first use: 8 px from the left, a quarter of the window wide
// (viewer/panel.h), and a few pixels of its border.
constexpr int kPanelRight = 8 + kWidth / 4 + 4;
constexpr float kCoveredLeft = float(8 + kWidth / 4) / float(kWidth);
constexpr double kFrameDt = 0.02;

using Image = std::vector<std::uint8_t>;
using Colour = std::array<double, 3>;

// A colour's chromaticity: each channel's share of the sum, so that light and shade compare.
Colour chroma(const Colour& c) {
  const double sum = c[0] + c[1] + c[2];
  if (sum <= 0.0) return {1.0 / 3, 1.0 / 3, 1.0 / 3};
  return {c[0] / sum, c[1] / sum, c[2] / sum};
}

double distance(const Colour& a, const Colour& b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                   (a[2] - b[2]) * (a[2] - b[2]));
}

// The renderer's grains are tan to orange: red over green over blue, red under half the sum (as
// the viewer tests tell them).
bool sandColoured(const std::uint8_t* p) {
  return p[0] > 90 && p[0] > p[1] + 12 && p[1] > p[2] + 12 && 2 * p[0] < p[0] + p[1] + p[2];
}

struct BodyScene {
  const char* name;
  // Simulated time to run before the picture, s: the body is in the scene by then (rock-drop
  // drops its rock once the bed has settled).
  double seconds;
};

class BodySurfaces : public ::testing::TestWithParam<BodyScene> {};

TEST_P(BodySurfaces, ShowBesideThePanelInTheirMaterialColour) {
  const BodyScene& param = GetParam();
  std::unique_ptr<scenes::Scene> scene = scenes::createScene(param.name);
  ASSERT_TRUE(scene);
  scenes::useTestSize(*scene);
  World world(gpu(), scene->settings());
  scene->build(world);
  while (world.simulatedTime() < param.seconds) {
    const StepReport report = scene->step(world, float(kFrameDt));
    scene->update(world, report, world.simulatedTime());
  }
  const std::vector<scenes::SceneSurface> surfaces(scene->surfaces().begin(),
                                                   scene->surfaces().end());
  ASSERT_FALSE(surfaces.empty()) << param.name << " has no body surfaces after " << param.seconds
                                 << " s";

  const render::Camera camera = render::Camera::framing(
      scene->view(scenes::contentsOf(*scene, world)), float(kWidth) / float(kHeight), kCoveredLeft);
  render::OffscreenTarget target(kWidth, kHeight);
  render::Renderer renderer;
  renderer.settings().shadows = false;
  renderer.settings().aoSamples = 0;
  auto draw = [&](std::span<const scenes::SceneSurface> shown) {
    target.bind();
    renderer.draw(world, camera, scene->bounds(), kWidth, kHeight, shown);
    return target.readRgba();
  };
  const Image all = draw(surfaces);

  std::vector<bool> onBody(std::size_t(kWidth) * kHeight, false);
  std::vector<Colour> bodyColours;
  for (std::size_t k = 0; k < surfaces.size(); ++k) {
    std::vector<scenes::SceneSurface> without = surfaces;
    without[k].mesh.triangles.clear();  // its particles stay hidden: only its surface goes
    const Image rest = draw(without);
    long pixels = 0;
    Colour sum{};
    for (int y = 0; y < kHeight; ++y) {
      for (int x = kPanelRight; x < kWidth; ++x) {
        const std::size_t i = std::size_t(y) * kWidth + std::size_t(x);
        const std::uint8_t* a = &all[4 * i];
        const std::uint8_t* b = &rest[4 * i];
        if (std::abs(a[0] - b[0]) + std::abs(a[1] - b[1]) + std::abs(a[2] - b[2]) <= 6) continue;
        onBody[i] = true;
        ++pixels;
        for (int c = 0; c < 3; ++c) sum[c] += a[c];
      }
    }
    std::printf("%s body %zu (slot %u): %ld pixels beside the panel\n", param.name, k,
                surfaces[k].body.index, pixels);
    EXPECT_GE(pixels, 100) << param.name << " body " << k << " is not seen beside the panel";
    bodyColours.push_back(pixels > 0 ? Colour{sum[0] / pixels, sum[1] / pixels, sum[2] / pixels}
                                     : Colour{});
  }

  long sandPixels = 0;
  Colour sand{};
  for (int y = 0; y < kHeight; ++y) {
    for (int x = kPanelRight; x < kWidth; ++x) {
      const std::size_t i = std::size_t(y) * kWidth + std::size_t(x);
      if (onBody[i] || !sandColoured(&all[4 * i])) continue;
      ++sandPixels;
      for (int c = 0; c < 3; ++c) sand[c] += all[4 * i + c];
    }
  }
  ASSERT_GT(sandPixels, 200) << param.name << ": no sand beside the panel";
  for (double& c : sand) c /= double(sandPixels);

  for (std::size_t k = 0; k < surfaces.size(); ++k) {
    const Eigen::Vector3f m =
        renderer.settings().materialColours[std::size_t(surfaces[k].material)];
    const Colour material = chroma({m.x(), m.y(), m.z()});
    const Colour body = chroma(bodyColours[k]);
    const double toMaterial = distance(body, material);
    const double toSand = distance(body, chroma(sand));
    std::printf(
        "%s body %zu: chromaticity %.3f %.3f %.3f; %.3f from its material's, %.3f from "
        "the sand's\n",
        param.name, k, body[0], body[1], body[2], toMaterial, toSand);
    EXPECT_LT(toMaterial, 0.05) << param.name << " body " << k << " is not in its material colour";
    EXPECT_LT(toMaterial, toSand) << param.name << " body " << k << " looks like sand";
  }

  // The debug view draws the bodies as their particles, exactly as with no surfaces at all.
  const Image particles = draw({});
  EXPECT_NE(particles, all);
  renderer.settings().bodyParticles = true;
  EXPECT_EQ(draw(surfaces), particles) << "'bodies as particles' still draws a surface";
}

INSTANTIATE_TEST_SUITE_P(ScenesWithBodies, BodySurfaces,
                         ::testing::Values(BodyScene{"avalanche", 0.1}, BodyScene{"bulldozer", 0.1},
                                           BodyScene{"compression", 0.1},
                                           BodyScene{"rock-drop", 1.0}),
                         [](const ::testing::TestParamInfo<BodyScene>& entry) {
                           std::string name = entry.param.name;
                           for (char& c : name) c = c == '-' ? '_' : c;
                           return name;
                         });

}  // namespace
}  // namespace sandphys::testing
