#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <memory>
#include <span>

#include <sandphys/world.h>

#include "render/camera.h"
#include "scenes/scene.h"

namespace sandphys::render {

/// A directional light (the sun).
struct Light {
  /// Unit vector from the scene towards the light (world); normalised by the renderer.
  Eigen::Vector3f direction = Eigen::Vector3f(0.55f, 0.75f, 0.35f).normalized();
  /// Direct irradiance, linear RGB (1 = white paper in full light).
  Eigen::Vector3f colour{2.6f, 2.45f, 2.2f};
  /// Ambient light from the sky (surfaces facing up), linear RGB.
  Eigen::Vector3f sky{0.36f, 0.40f, 0.48f};
  /// Ambient light bounced from the ground (surfaces facing down), linear RGB.
  Eigen::Vector3f ground{0.16f, 0.14f, 0.11f};
};

/// How the Renderer draws. Every field may change between frames.
struct RenderSettings {
  Light light;
  /// Colour where nothing is drawn, sRGB in [0, 1].
  Eigen::Vector3f background{0.70f, 0.76f, 0.82f};
  /// Fraction of the viewport's width and height at which the scene is lit and composited, in
  /// [0.25, 1]; below 1 the result is scaled up to the viewport (cheaper, softer).
  float renderScale = 1.0f;
  /// Side of the square shadow map, texels; in 16..8192.
  int shadowMapSize = 2048;
  /// Direct light is shadowed (granules shadow themselves, each other and the colliders).
  bool shadows = true;
  /// Screen-space ambient occlusion samples per radius and pixel; 0 turns it off.
  int aoSamples = 12;
  /// Radius of the fine ambient-occlusion pass, in particle diameters; the coarse pass uses six
  /// times it.
  float aoRadius = 1.5f;
  /// Colliders are drawn (a plane as a square of 40 camera distances).
  bool drawColliders = true;
  /// Sleeping granules (WorldSettings::sleep) are drawn tinted blue-grey.
  bool tintSleeping = false;
  /// Colour of each scenes::BodyMaterial (wood, stone, metal), sRGB in [0, 1].
  std::array<Eigen::Vector3f, scenes::kBodyMaterials> materialColours = {
      Eigen::Vector3f{0.46f, 0.26f, 0.14f}, Eigen::Vector3f{0.47f, 0.46f, 0.44f},
      Eigen::Vector3f{0.40f, 0.44f, 0.50f}};
  /// Bodies that have a surface (Scene::surfaces) are drawn as their particles instead, as the
  /// sand sees them (a debug view).
  bool bodyParticles = false;
};

/// GPU time of the last frame whose timer queries were ready, measured with GL_TIMESTAMP
/// (llvmpipe reports 0 for GL_TIME_ELAPSED). Separate from the simulation's kernel times.
struct RenderStats {
  double shadowMs = 0.0;     ///< depth of impostors and colliders from the light
  double sceneMs = 0.0;      ///< lit impostors and colliders into the renderer's own targets
  double compositeMs = 0.0;  ///< ambient occlusion and final colour (and the scale-up, if any)
  double totalMs = 0.0;      ///< the three passes
  int renderWidth = 0;       ///< size the scene was lit at (the viewport times renderScale), px
  int renderHeight = 0;
  std::uint32_t particles = 0;  ///< particles drawn (of alive and dead bodies)
  std::uint64_t frame = 0;      ///< draws completed so far when these times were taken
};

/// Draws a World's particles as ray-cast sphere impostors straight from its GPU buffers (see
/// sandphys/gl_interop.h), its colliders as meshes, a directional light with a shadow map, and a
/// screen-space ambient-occlusion term. Needs the World's OpenGL 4.5 context to be current for
/// its whole life (creation compiles the shaders and throws GpuError naming file and line).
class Renderer {
 public:
  Renderer();
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  RenderSettings& settings();
  const RenderSettings& settings() const;

  /// Draws `world` seen by `camera` into the currently bound draw framebuffer at viewport (0, 0,
  /// width, height), writing colour and depth. The shadow map covers `shadowBounds` (m, world):
  /// give the scene's bounds. The bodies of `surfaces` (Scene::surfaces) are drawn as those
  /// surfaces in their materials, the rest as their particles; the surfaces are uploaded when
  /// they differ from the last draw's. No read-back: the timer queries are read a frame later.
  void draw(const World& world, const Camera& camera, const scenes::SceneBounds& shadowBounds,
            int width, int height, std::span<const scenes::SceneSurface> surfaces = {});

  /// Times of the newest frame whose queries are ready (no wait).
  const RenderStats& stats() const;
  /// Waits for the last draw's queries and returns its times. Sync point.
  const RenderStats& finishStats();

 private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

}  // namespace sandphys::render
