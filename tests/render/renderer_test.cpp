// The samples' renderer on llvmpipe: a small settled pile drawn from the World's buffers, seen
// from a fixed camera under a low sun. Checks what a person would look for: sand where the pile
// is, background where nothing is, the pile's shadow on the floor, a collider drawn, and PNG files
// that hold exactly the rendered pixels.
#include <gtest/gtest.h>
#include <stb/stb_image.h>

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <sandphys/gl_interop.h>

#include "render/camera.h"
#include "render/offscreen_target.h"
#include "render/png.h"
#include "render/render_quality.h"
#include "render/renderer.h"
#include "support/test_world.h"

namespace sandphys::testing {
namespace {

constexpr float kD = 0.02f;              // particle diameter, m
constexpr float kFloorRadius = 24 * kD;  // rough floor disc, m
constexpr int kWidth = 320;
constexpr int kHeight = 240;
// The obstacle box beside the pile, on the light's side and clear of the sand.
const Vec3 kBoxCentre{0.44f, 0.06f, -0.30f};
const Vec3 kBoxHalf{0.04f, 0.04f, 0.04f};

using Image = std::vector<std::uint8_t>;

struct Pixel {
  int r, g, b;
};

Pixel pixelAt(const Image& image, int x, int y) {
  const std::size_t i = (std::size_t(y) * kWidth + std::size_t(x)) * 4;
  return {image[i], image[i + 1], image[i + 2]};
}

double luminance(Pixel p) {
  return 0.2126 * p.r + 0.7152 * p.g + 0.0722 * p.b;
}

// Tan to ochre, lit or in shade: red well above blue (by a fifth of red), green between. The
// neutral floor and collider and the blue-grey background are not.
bool sandColoured(Pixel p) {
  return p.r >= p.g && p.g >= p.b && p.r > 25 && 5 * (p.r - p.b) > p.r;
}

// A heap of 250 granules dropped as a column onto a rough floor, settled with a soft, well damped
// material: a large time step, so settling takes seconds on llvmpipe, not minutes. The render
// only needs a heap's shape, not a stiff sand's overlaps: the paper's contact law, whose overlap
// cap takes a material this soft (ContactLaw::HertzMindlin refuses it).
class RenderScene : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    WorldSettings s = smallSettings(512);
    s.particleDiameter = kD;
    s.material.youngsModulus = 2.0e5f;
    s.material.restitution = 0.2f;
    s.material.friction = 0.7f;
    s.maxSpeed = 3.0f;
    s.contactLaw = ContactLaw::PaperViscous;
    s.maxParticles = 4 * 512 + 2000;
    world = new World(gpu(), s);
    world->addRoughFloor(RoughFloor{.center = {0.0f, 0.0f, 0.0f}, .radius = kFloorRadius});
    world->addCollider(Box{.center = kBoxCentre, .halfExtents = kBoxHalf, .inside = false});
    world->addGranules(GranuleBlock{.center = {0.0f, 0.27f, 0.0f},
                                    .countX = 5,
                                    .countY = 10,
                                    .countZ = 5,
                                    .spacing = 2.4f * kD,
                                    .seed = 3});
    const auto start = std::chrono::steady_clock::now();
    const auto steps = std::uint32_t(std::ceil(1.2 / world->timeStep()));
    world->substep(steps);
    bodies = world->readBodies();
    std::printf("settled the pile in %u substeps of %.3g s: %.1f s wall\n", steps,
                double(world->timeStep()),
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  static void TearDownTestSuite() {
    delete world;
    world = nullptr;
  }

  static render::Camera camera() {
    render::Camera c;
    c.target = {0.0f, 0.04f, 0.0f};
    c.distance = 1.25f;
    c.yaw = 0.0f;  // eye on +z, the light comes from +x: the shadow falls to the left
    c.pitch = 0.72f;
    c.fovY = 0.75f;
    return c;
  }

  static scenes::SceneBounds bounds() {
    return {{-kFloorRadius - kD, -kD, -kFloorRadius - kD},
            {kFloorRadius + kD, 0.3f, kFloorRadius + kD}};
  }

  // Renders with `settings` into a fresh offscreen target and reads the pixels back.
  static Image drawImage(const render::RenderSettings& settings,
                         render::RenderStats* stats = nullptr, const char* pngName = nullptr,
                         const render::Camera& view = camera()) {
    render::OffscreenTarget target(kWidth, kHeight);
    render::Renderer renderer;
    renderer.settings() = settings;
    target.bind();
    renderer.draw(*world, view, bounds(), kWidth, kHeight);
    Image image = target.readRgba();
    if (stats) *stats = renderer.finishStats();
    if (pngName) {
      render::writePng(std::filesystem::path(SANDPHYS_RENDER_TEST_OUTPUT) / pngName, kWidth,
                       kHeight, image);
    }
    return image;
  }

  static render::RenderSettings lowSun() {
    render::RenderSettings s;
    // 12 degrees above the horizon from +x: the heap's shadow reaches well past its foot.
    const float elevation = 12.0f * 3.14159265f / 180.0f;
    s.light.direction = {std::cos(elevation), std::sin(elevation), 0.0f};
    s.shadowMapSize = 1024;
    return s;
  }

  // Pixel (x right, y down) of a world point, and whether it is in the image.
  static bool project(const Eigen::Vector3f& p, float* x, float* y) {
    const Eigen::Matrix4f m = camera().projection(float(kWidth) / kHeight) * camera().view();
    const Eigen::Vector4f clip = m * Eigen::Vector4f(p.x(), p.y(), p.z(), 1.0f);
    if (clip.w() <= 0.0f) return false;
    *x = (clip.x() / clip.w() * 0.5f + 0.5f) * kWidth;
    *y = (1.0f - (clip.y() / clip.w() * 0.5f + 0.5f)) * kHeight;
    return *x >= 0 && *y >= 0 && *x < kWidth && *y < kHeight;
  }

  struct Rect {
    float x0 = 1e9f, y0 = 1e9f, x1 = -1e9f, y1 = -1e9f;
    void add(float x, float y) {
      x0 = std::min(x0, x);
      y0 = std::min(y0, y);
      x1 = std::max(x1, x);
      y1 = std::max(y1, y);
    }
    bool contains(int x, int y, float margin) const {
      return x >= x0 - margin && x <= x1 + margin && y >= y0 - margin && y <= y1 + margin;
    }
  };

  // The projection of an axis-aligned box (all eight corners).
  static Rect projectBox(const Eigen::Vector3f& lo, const Eigen::Vector3f& hi) {
    Rect rect;
    for (int corner = 0; corner < 8; ++corner) {
      const Eigen::Vector3f p((corner & 1) ? hi.x() : lo.x(), (corner & 2) ? hi.y() : lo.y(),
                              (corner & 4) ? hi.z() : lo.z());
      float x = 0, y = 0;
      project(p, &x, &y);
      rect.add(x, y);
    }
    return rect;
  }

  // Bounding box of the granules' particles within `radius` of the axis, from the read-back
  // centres, m.
  static void pileBox(float radius, Eigen::Vector3f* lo, Eigen::Vector3f* hi) {
    const float reach = 0.6124f * kD + 0.5f * kD;  // tetrahedron circumradius + particle radius
    *lo = Eigen::Vector3f::Constant(1e9f);
    *hi = Eigen::Vector3f::Constant(-1e9f);
    for (const BodyState& b : bodies) {
      if (!b.granule || !b.alive || std::hypot(b.position.x, b.position.z) > radius) continue;
      const Eigen::Vector3f p(b.position.x, b.position.y, b.position.z);
      *lo = lo->cwiseMin(p - Eigen::Vector3f::Constant(reach));
      *hi = hi->cwiseMax(p + Eigen::Vector3f::Constant(reach));
    }
  }

  // Radius around the axis that holds 95% of the granules, m.
  static float pileRadius() {
    std::vector<float> r;
    for (const BodyState& b : bodies) {
      if (b.granule && b.alive) r.push_back(std::hypot(b.position.x, b.position.z));
    }
    std::sort(r.begin(), r.end());
    return r[r.size() * 95 / 100];
  }

  // Mean luminance of the floor in a square of side 3 d around (x, z), sampled at the tops of
  // the floor's particles.
  static double floorLuminance(const Image& image, float x, float z) {
    double sum = 0.0;
    int n = 0;
    for (int i = -3; i <= 3; ++i) {
      for (int j = -3; j <= 3; ++j) {
        float px = 0, py = 0;
        if (!project({x + i * 0.5f * kD, 0.5f * kD, z + j * 0.5f * kD}, &px, &py)) continue;
        sum += luminance(pixelAt(image, int(px), int(py)));
        ++n;
      }
    }
    EXPECT_GT(n, 40) << "region around (" << x << ", " << z << ") is off screen";
    return n ? sum / n : 0.0;
  }

  // The floor `r` beyond the foot of the heap: downwind of the light (-x), in the heap's shadow,
  // and at the same distance across the light (+z, towards the camera), in full sun.
  struct FloorLight {
    double behind = 0.0;
    double across = 0.0;
  };
  static FloorLight floorLight(const Image& image, float r) {
    return {floorLuminance(image, -r, 0.0f), floorLuminance(image, 0.0f, r)};
  }

  static World* world;
  static std::vector<BodyState> bodies;
};

World* RenderScene::world = nullptr;
std::vector<BodyState> RenderScene::bodies;

TEST_F(RenderScene, PileIsSandInsideItsProjectedBoxAndBackgroundElsewhere) {
  const render::RenderSettings settings = lowSun();
  const Image image = drawImage(settings, nullptr, "pile.png");

  // The heap: the granules within the radius that holds 95% of them (a few bounce far away;
  // they count as the pile's for the stray check below).
  Eigen::Vector3f lo, hi;
  pileBox(pileRadius(), &lo, &hi);
  ASSERT_GT(hi.y() - lo.y(), 4 * kD) << "the granules did not form a heap";
  const Rect pile = projectBox(lo, hi);
  Eigen::Vector3f allLo, allHi;
  pileBox(1e9f, &allLo, &allHi);
  const Rect wholePile = projectBox(allLo, allHi);
  // Everything drawn: the pile, the floor disc (its particles reach d/2 up and out), the box.
  const Eigen::Vector3f floorLo(-kFloorRadius - kD, -kD, -kFloorRadius - kD);
  const Eigen::Vector3f floorHi(kFloorRadius + kD, kD, kFloorRadius + kD);
  const Eigen::Vector3f boxLo(kBoxCentre.x - kBoxHalf.x, kBoxCentre.y - kBoxHalf.y,
                              kBoxCentre.z - kBoxHalf.z);
  const Eigen::Vector3f boxHi(kBoxCentre.x + kBoxHalf.x, kBoxCentre.y + kBoxHalf.y,
                              kBoxCentre.z + kBoxHalf.z);
  const Rect all =
      projectBox(allLo.cwiseMin(floorLo).cwiseMin(boxLo), allHi.cwiseMax(floorHi).cwiseMax(boxHi));

  const Pixel background{int(std::lround(settings.background.x() * 255)),
                         int(std::lround(settings.background.y() * 255)),
                         int(std::lround(settings.background.z() * 255))};
  int inside = 0, sand = 0, outside = 0, notBackground = 0;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const Pixel p = pixelAt(image, x, y);
      if (pile.contains(x, y, 0.0f)) {
        ++inside;
        sand += sandColoured(p);
      } else if (!all.contains(x, y, 2.0f)) {
        ++outside;
        notBackground += std::abs(p.r - background.r) > 1 || std::abs(p.g - background.g) > 1 ||
                         std::abs(p.b - background.b) > 1;
      }
    }
  }
  ASSERT_GT(inside, 2000) << "the pile covers too little of the image to judge";
  ASSERT_GT(outside, 5000) << "no background left around the scene";
  // The projected box of a heap also holds floor around its base: about half sand is expected.
  EXPECT_GT(double(sand) / inside, 0.4) << sand << " of " << inside << " pixels are sand";
  EXPECT_EQ(notBackground, 0) << "of " << outside << " pixels outside the scene";
  // And no sand outside the pile's box.
  int strays = 0;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      if (!wholePile.contains(x, y, 2.0f)) strays += sandColoured(pixelAt(image, x, y));
    }
  }
  EXPECT_LT(strays, 20) << "sand-coloured pixels outside the pile's projected box";
}

TEST_F(RenderScene, PileShadowsTheFloorBehindIt) {
  const float r = 1.3f * pileRadius();
  ASSERT_LT(r + 2 * kD, kFloorRadius);
  render::RenderSettings settings = lowSun();
  const FloorLight shadowed = floorLight(drawImage(settings, nullptr, "pile_shadow.png"), r);
  EXPECT_GT(shadowed.across, 1.6 * shadowed.behind)
      << "lit floor " << shadowed.across << ", floor behind the pile " << shadowed.behind;

  // Without the shadow map both regions get the same light: this test measures the shadow.
  settings.shadows = false;
  const FloorLight unshadowed = floorLight(drawImage(settings, nullptr, "pile_no_shadow.png"), r);
  EXPECT_LT(unshadowed.across, 1.2 * unshadowed.behind)
      << unshadowed.across << " vs " << unshadowed.behind;
  EXPECT_GT(unshadowed.behind, 1.3 * shadowed.behind)
      << "the shadow map made no difference behind the pile";
}

TEST_F(RenderScene, ColliderIsDrawnInANeutralMaterial) {
  const Image image = drawImage(lowSun());
  float x = 0, y = 0;
  // The middle of the box's top face.
  ASSERT_TRUE(project({kBoxCentre.x, kBoxCentre.y + kBoxHalf.y, kBoxCentre.z}, &x, &y));
  const Pixel p = pixelAt(image, int(x), int(y));
  EXPECT_LT(std::abs(p.r - p.b), 40) << p.r << " " << p.g << " " << p.b;
  EXPECT_GT(luminance(p), 60.0);
  const render::RenderSettings defaults;
  EXPECT_GT(std::abs(p.r - int(defaults.background.x() * 255)) +
                std::abs(p.b - int(defaults.background.z() * 255)),
            20)
      << "the box's pixel looks like background";
}

// Seen from behind the obstacle box, the box hides the pile's middle; once the camera is framed
// on the pile (Camera::focus), the box is drawn see-through and the sand shows through it.
TEST_F(RenderScene, ColliderBetweenTheEyeAndTheFocusIsSeeThrough) {
  render::Camera behindBox;
  behindBox.target = {0.0f, 0.05f, 0.0f};
  behindBox.yaw = std::atan2(kBoxCentre.x, kBoxCentre.z);  // the eye on the box's side
  behindBox.pitch = 0.05f;
  behindBox.distance = 0.9f;
  // The box's face towards the eye, shrunk by a pixel's worth: what of the picture it covers.
  const Eigen::Matrix4f m = behindBox.projection(float(kWidth) / kHeight) * behindBox.view();
  Rect face;
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector4f p(kBoxCentre.x + ((corner & 1) ? 0.8f : -0.8f) * kBoxHalf.x,
                            kBoxCentre.y + ((corner & 2) ? 0.8f : -0.8f) * kBoxHalf.y,
                            kBoxCentre.z + ((corner & 4) ? 0.8f : -0.8f) * kBoxHalf.z, 1.0f);
    const Eigen::Vector4f clip = m * p;
    face.add((clip.x() / clip.w() * 0.5f + 0.5f) * kWidth,
             (1.0f - (clip.y() / clip.w() * 0.5f + 0.5f)) * kHeight);
  }
  auto sandUnderBox = [&](const Image& image) {
    long count = 0;
    for (int y = 0; y < kHeight; ++y) {
      for (int x = 0; x < kWidth; ++x) {
        if (face.contains(x, y, -1.0f) && sandColoured(pixelAt(image, x, y))) ++count;
      }
    }
    return count;
  };
  const long hidden = sandUnderBox(drawImage(lowSun(), nullptr, "behind_box.png", behindBox));
  Eigen::Vector3f lo, hi;
  pileBox(kFloorRadius, &lo, &hi);
  behindBox.focus = scenes::SceneBounds{{lo.x(), lo.y(), lo.z()}, {hi.x(), hi.y(), hi.z()}};
  const long shown =
      sandUnderBox(drawImage(lowSun(), nullptr, "behind_box_see_through.png", behindBox));
  std::printf("sand pixels over the box's face: %ld opaque, %ld see-through\n", hidden, shown);
  EXPECT_LT(hidden, 20) << "the box does not hide the pile from this eye";
  EXPECT_GT(shown, 200) << "the box still hides the pile it stands in front of";
}

TEST_F(RenderScene, StatsMeasureTheRenderPassesSeparately) {
  render::RenderStats stats;
  drawImage(lowSun(), &stats);
  EXPECT_EQ(stats.particles, world->particleCount());
  EXPECT_EQ(stats.frame, 1u);
  EXPECT_GT(stats.totalMs, 0.0);
  EXPECT_GT(stats.shadowMs, 0.0);
  EXPECT_GT(stats.sceneMs, 0.0);
  EXPECT_GT(stats.compositeMs, 0.0);
  EXPECT_NEAR(stats.totalMs, stats.shadowMs + stats.sceneMs + stats.compositeMs, 1e-3);
  std::printf("render %dx%d of %u particles: shadow %.1f ms, scene %.1f ms, composite %.1f ms\n",
              kWidth, kHeight, stats.particles, stats.shadowMs, stats.sceneMs, stats.compositeMs);
}

// The cost presets trade resolution, shadow-map texels and AO samples for time; each must still
// draw the same pile with its shadow, at the size it says.
TEST_F(RenderScene, EveryQualityShowsThePileAndItsShadowAtItsScale) {
  const float r = 1.3f * pileRadius();
  render::RenderSettings high = lowSun();
  render::applyRenderQuality(render::RenderQuality::High, high);
  const Image reference = drawImage(high);
  for (const render::RenderQuality quality :
       {render::RenderQuality::Low, render::RenderQuality::Medium, render::RenderQuality::High}) {
    const std::string name(render::renderQualityName(quality));
    render::RenderSettings settings = lowSun();
    render::applyRenderQuality(quality, settings);
    render::RenderStats stats;
    const Image image = drawImage(settings, &stats, ("quality_" + name + ".png").c_str());
    EXPECT_EQ(stats.renderWidth, int(std::lround(kWidth * settings.renderScale))) << name;
    EXPECT_EQ(stats.renderHeight, int(std::lround(kHeight * settings.renderScale))) << name;
    // The shadow, measured against the same preset without it: at the low preset it darkens the
    // floor behind the pile 1.7 times and leaves the lit floor 1.6 times as bright as that (Mesa
    // 22.3 and 25.0; the pile settles differently on each), where without it the two differ by
    // under 1.2 (PileShadowsTheFloorBehindIt).
    const FloorLight shadowed = floorLight(image, r);
    render::RenderSettings withoutShadows = settings;
    withoutShadows.shadows = false;
    const FloorLight unshadowed = floorLight(drawImage(withoutShadows), r);
    EXPECT_GT(unshadowed.behind, 1.5 * shadowed.behind)
        << name << ": behind the pile " << shadowed.behind << ", " << unshadowed.behind
        << " without the shadow";
    EXPECT_GT(shadowed.across, 1.4 * shadowed.behind)
        << name << ": lit floor " << shadowed.across << ", behind the pile " << shadowed.behind;
    // Same picture as the best preset: compared in blocks of 8x8 pixels, because a grain a few
    // pixels wide is necessarily softer when lit at half the resolution.
    constexpr int kBlock = 8;
    double difference = 0.0;
    for (int by = 0; by < kHeight / kBlock; ++by) {
      for (int bx = 0; bx < kWidth / kBlock; ++bx) {
        double a = 0.0, b = 0.0;
        for (int y = by * kBlock; y < (by + 1) * kBlock; ++y) {
          for (int x = bx * kBlock; x < (bx + 1) * kBlock; ++x) {
            a += luminance(pixelAt(image, x, y));
            b += luminance(pixelAt(reference, x, y));
          }
        }
        difference += std::abs(a - b) / (kBlock * kBlock);
      }
    }
    difference /= double(kWidth / kBlock) * (kHeight / kBlock);
    EXPECT_LT(difference, 4.0) << name << ": mean luminance difference from high, 8x8 blocks";
    std::printf(
        "%-6s %dx%d, shadow map %d, AO %d: shadow %.1f ms, scene %.1f ms, composite %.1f ms, "
        "mean |dL| from high %.2f\n",
        name.c_str(), stats.renderWidth, stats.renderHeight, settings.shadowMapSize,
        settings.aoSamples, stats.shadowMs, stats.sceneMs, stats.compositeMs, difference);
  }
}

// Particles are point sprites, which GL limits in size (255 px on llvmpipe); a close-up needs
// larger squares, drawn as quads. Looking down at the highest particle through a narrow lens, it
// and its neighbours are several hundred pixels wide: the middle of the image must be that sand
// grain, not the floor far below it or the background.
TEST_F(RenderScene, CloseUpDrawsGrainsLargerThanAPointSprite) {
  const std::vector<ParticleState> particles = world->readParticles();
  const ParticleState* top = nullptr;
  for (const ParticleState& p : particles) {
    if (!top || p.position.y > top->position.y) top = &p;
  }
  ASSERT_NE(top, nullptr);
  render::Camera close;
  close.target = {top->position.x, top->position.y, top->position.z};
  close.distance = 4.0f * kD;
  close.pitch = 1.3f;
  close.yaw = 0.3f;
  close.fovY = 0.1f;
  // Diameter on screen of a grain at the target: about 600 px, more than any point sprite.
  const float focalPx = 0.5f * kHeight / std::tan(0.5f * close.fovY);
  ASSERT_GT(kD * focalPx / close.distance, 300.0f);
  const Image image = drawImage(render::RenderSettings{}, nullptr, "close_up.png", close);
  int sand = 0, total = 0;
  for (int y = kHeight / 2 - 20; y < kHeight / 2 + 20; ++y) {
    for (int x = kWidth / 2 - 20; x < kWidth / 2 + 20; ++x) {
      sand += sandColoured(pixelAt(image, x, y));
      ++total;
    }
  }
  EXPECT_EQ(sand, total) << "the middle of a close-up of the highest grain is not all sand";
}

TEST(RenderQuality, NamesParseBackAndStepsSaturate) {
  for (const render::RenderQuality quality :
       {render::RenderQuality::Low, render::RenderQuality::Medium, render::RenderQuality::High}) {
    EXPECT_EQ(render::parseRenderQuality(render::renderQualityName(quality)), quality);
  }
  EXPECT_FALSE(render::parseRenderQuality("ultra").has_value());
  EXPECT_EQ(render::lowerQuality(render::RenderQuality::Low), render::RenderQuality::Low);
  EXPECT_EQ(render::higherQuality(render::RenderQuality::High), render::RenderQuality::High);
  EXPECT_EQ(render::higherQuality(render::RenderQuality::Low), render::RenderQuality::Medium);
  // Cheaper presets never cost more on any axis.
  render::RenderSettings low, medium, high;
  render::applyRenderQuality(render::RenderQuality::Low, low);
  render::applyRenderQuality(render::RenderQuality::Medium, medium);
  render::applyRenderQuality(render::RenderQuality::High, high);
  EXPECT_LT(low.renderScale, medium.renderScale);
  EXPECT_LT(medium.renderScale, high.renderScale);
  EXPECT_LE(low.shadowMapSize, medium.shadowMapSize);
  EXPECT_LE(medium.shadowMapSize, high.shadowMapSize);
  EXPECT_LT(low.aoSamples, medium.aoSamples);
  EXPECT_LT(medium.aoSamples, high.aoSamples);
}

TEST_F(RenderScene, PngHoldsExactlyTheRenderedPixels) {
  const Image image = drawImage(lowSun());
  const std::filesystem::path path =
      std::filesystem::path(SANDPHYS_RENDER_TEST_OUTPUT) / "round_trip.png";
  render::writePng(path, kWidth, kHeight, image);
  int w = 0, h = 0, channels = 0;
  std::unique_ptr<stbi_uc, void (*)(void*)> loaded(stbi_load(path.c_str(), &w, &h, &channels, 4),
                                                   stbi_image_free);
  ASSERT_NE(loaded, nullptr) << stbi_failure_reason();
  ASSERT_EQ(w, kWidth);
  ASSERT_EQ(h, kHeight);
  std::size_t differing = 0;
  for (std::size_t i = 0; i < image.size(); ++i) differing += loaded.get()[i] != image[i];
  EXPECT_EQ(differing, 0u);
}

TEST_F(RenderScene, InteropExposesTheWorldsBuffersAndColliders) {
  const RenderBuffers b = renderBuffers(*world);
  EXPECT_EQ(b.bodyCount, world->bodyCount());
  EXPECT_EQ(b.particleCount, world->particleCount());
  EXPECT_EQ(b.particleDiameter, kD);
  const std::array<unsigned, 6> names = {b.bodyPosition,  b.bodyOrientation, b.bodyInfo,
                                         b.particleLocal, b.particleBody,    b.particlePosition};
  for (std::size_t i = 0; i < names.size(); ++i) {
    EXPECT_NE(names[i], 0u) << i;
    for (std::size_t j = 0; j < i; ++j) EXPECT_NE(names[i], names[j]) << i << " " << j;
  }
  const std::vector<ColliderShape> colliders = world->colliders();
  ASSERT_EQ(colliders.size(), 1u);
  const Box* box = std::get_if<Box>(&colliders[0]);
  ASSERT_NE(box, nullptr);
  EXPECT_EQ(box->center.x, kBoxCentre.x);
  EXPECT_EQ(box->halfExtents.y, kBoxHalf.y);
  EXPECT_FALSE(box->inside);
}

// Adds a collider to the shared world, so it comes after every other test of the fixture
// (GoogleTest runs them in the order of this file). A plane is solid on one side; a camera inside
// the solid (the avalanche scene's moved-away retaining wall, say) must still see the scene through
// it.
TEST_F(RenderScene, PlaneSeenFromItsSolidSideHidesNothing) {
  const render::RenderSettings settings = lowSun();
  const auto countSand = [](const Image& image) {
    int sand = 0;
    for (int y = 0; y < kHeight; ++y) {
      for (int x = 0; x < kWidth; ++x) sand += sandColoured(pixelAt(image, x, y));
    }
    return sand;
  };
  const int before = countSand(drawImage(settings));
  ASSERT_GT(before, 2000);
  // Solid where z > 0.6 m: the eye (z = 0.94 m) is inside, the pile (|z| < 0.3 m) is not.
  const Eigen::Vector3f eye = camera().eye();
  ASSERT_GT(eye.z(), 0.6f);
  world->addCollider(Plane{.normal = {0.0f, 0.0f, -1.0f}, .offset = -0.6f});
  const int after = countSand(drawImage(settings));
  EXPECT_GT(after, 0.9 * before) << "sand pixels " << after << " with the plane, " << before
                                 << " without";
}

// A granule's colour is its body's (a hash of its id), wherever a sort of the granules by place
// puts its state: a World of granules added in a random order, drawn before and after a sort that
// moves most of them to other slots, gives the same image.
TEST(RenderSorted, GranulesKeepTheirColoursWhenSortedByPlace) {
  WorldSettings s = smallSettings(256);
  s.particleDiameter = kD;
  s.sortInterval = kNeverSortGranules - 1;  // sorted by sortGranulesNow alone
  World sorted(gpu(), s);
  sorted.addCollider(Plane{});
  std::vector<BodyDesc> granules;
  for (int k = 0; k < 8; ++k) {
    for (int i = 0; i < 8; ++i) {
      granules.push_back(
          {.position = {(float(i) - 3.5f) * 3 * kD, 2 * kD, (float(k) - 3.5f) * 3 * kD},
           .orientation = fromAxisAngle({0.0f, 1.0f, 0.0f}, 0.4f * float(i + 8 * k))});
    }
  }
  // Reversed rows, each reversed: the slots run against the grid's order.
  std::reverse(granules.begin(), granules.end());
  sorted.addGranules(granules);
  sorted.substep(1);  // the lists (and grid) a sort orders by
  const auto draw = [&] {
    render::OffscreenTarget target(kWidth, kHeight);
    render::Renderer renderer;
    render::Camera view;
    view.target = {0.0f, 0.0f, 0.0f};
    view.distance = 0.9f;
    view.pitch = 0.9f;
    target.bind();
    renderer.draw(sorted, view, {{-0.15f, -kD, -0.15f}, {0.15f, 0.1f, 0.15f}}, kWidth, kHeight);
    return target.readRgba();
  };
  const Image before = draw();
  const std::vector<ParticleState> particlesBefore = sorted.readParticles();
  sortGranulesNow(sorted);
  const std::vector<ParticleState> particlesAfter = sorted.readParticles();
  std::uint32_t moved = 0;
  for (std::size_t p = 0; p < particlesAfter.size(); p += 4) {
    moved += particlesAfter[p].body != particlesBefore[p].body;
  }
  ASSERT_GT(moved, 32u);
  const Image after = draw();
  std::uint32_t sand = 0;
  std::uint32_t differ = 0;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      sand += sandColoured(pixelAt(before, x, y));
      const Pixel a = pixelAt(before, x, y);
      const Pixel b = pixelAt(after, x, y);
      differ += a.r != b.r || a.g != b.g || a.b != b.b;
    }
  }
  EXPECT_GT(sand, 2000u);
  EXPECT_EQ(differ, 0u);
}

TEST(RenderPng, UnwritablePathThrowsNamingIt) {
  const Image pixels(4 * 4 * 4, 128);
  const std::string path = "/nonexistent-sandphys-dir/shot.png";
  try {
    render::writePng(path, 4, 4, pixels);
    FAIL() << "no error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find(path), std::string::npos) << error.what();
  }
  EXPECT_THROW(render::writePng("x.png", 5, 4, pixels), InvalidArgument);
}

TEST(RenderCamera, FramingShowsTheWholeBox) {
  const scenes::SceneBounds box{{-1.0f, 0.0f, -0.5f}, {1.0f, 2.0f, 0.5f}};
  const render::Camera camera = render::Camera::framing({box}, 16.0f / 9.0f);
  const Eigen::Matrix4f m = camera.projection(16.0f / 9.0f) * camera.view();
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector4f p((corner & 1) ? 1.0f : -1.0f, (corner & 2) ? 2.0f : 0.0f,
                            (corner & 4) ? 0.5f : -0.5f, 1.0f);
    const Eigen::Vector4f clip = m * p;
    EXPECT_LE(std::abs(clip.x() / clip.w()), 1.0f) << corner;
    EXPECT_LE(std::abs(clip.y() / clip.w()), 1.0f) << corner;
    EXPECT_LE(std::abs(clip.z() / clip.w()), 1.0f) << corner;
  }
}

// A view from any direction, with a panel over the left third: every corner of the focus lands
// in the rest of the picture, and the box fills it (no corner far inside on every side).
TEST(RenderCamera, FramingFitsTheFocusBesideThePanel) {
  const scenes::SceneBounds box{{-2.0f, 0.0f, -0.3f}, {1.0f, 0.5f, 0.7f}};
  for (const float covered : {0.0f, 0.25f, 1.0f / 3.0f}) {
    for (const float yaw : {0.0f, 0.6f, 2.5f, -1.2f}) {
      for (const float pitch : {0.1f, 0.45f, 1.2f}) {
        SCOPED_TRACE(::testing::Message()
                     << "covered " << covered << ", yaw " << yaw << ", pitch " << pitch);
        const float aspect = 16.0f / 10.0f;
        const render::Camera camera = render::Camera::framing({box, yaw, pitch}, aspect, covered);
        EXPECT_FLOAT_EQ(camera.yaw, yaw);
        EXPECT_FLOAT_EQ(camera.pitch, pitch);
        const Eigen::Matrix4f m = camera.projection(aspect) * camera.view();
        float left = 1.0f, right = -1.0f, bottom = 1.0f, top = -1.0f;
        float nearest = camera.distance;  // the nearest corner's depth, m
        for (int corner = 0; corner < 8; ++corner) {
          const Eigen::Vector4f p((corner & 1) ? box.max.x : box.min.x,
                                  (corner & 2) ? box.max.y : box.min.y,
                                  (corner & 4) ? box.max.z : box.min.z, 1.0f);
          const Eigen::Vector4f clip = m * p;
          nearest = std::min(nearest, clip.w());
          left = std::min(left, clip.x() / clip.w());
          right = std::max(right, clip.x() / clip.w());
          bottom = std::min(bottom, clip.y() / clip.w());
          top = std::max(top, clip.y() / clip.w());
        }
        // Clear of the panel (NDC x from -1 to -1 + 2 covered) and of the edges.
        EXPECT_GE(left, -1.0f + 2.0f * covered - 1e-4f);
        EXPECT_LE(right, 1.0f + 1e-4f);
        EXPECT_GE(bottom, -1.0f - 1e-4f);
        EXPECT_LE(top, 1.0f + 1e-4f);
        // Tight: in one direction at least the box spans nearly the free part, unless the eye
        // is as near as it can come (a long box seen end-on: its near end almost at the eye).
        const float freeWidth = 2.0f * (1.0f - covered);
        const float fill = std::max((right - left) / freeWidth, (top - bottom) / 2.0f);
        if (nearest > 0.1f * camera.distance) {
          EXPECT_GT(fill, 0.85f) << "nearest " << nearest;
        }
      }
    }
  }
}

}  // namespace
}  // namespace sandphys::testing
