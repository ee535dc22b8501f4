#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <sandphys/sandphys.h>

#include "scenes/scene.h"

namespace sandphys::bench {

/// Whether and how to time the renderer on each pile.
struct RenderOptions {
  /// Size of the frame, px; 0 = do not time rendering.
  int width = 0;
  int height = 0;
  /// Frames timed per quality preset, after one untimed frame (llvmpipe compiles the shaders'
  /// variants at their first draw).
  std::uint32_t frames = 4;
};

/// The renderer's cost at one quality preset, averaged per frame.
struct RenderTiming {
  std::string quality;  ///< render::renderQualityName
  int renderWidth = 0;  ///< the size it lit the scene at, px
  int renderHeight = 0;
  int shadowMapSize = 0;  ///< texels per side
  int aoSamples = 0;      ///< per radius and pixel
  double shadowMs = 0.0;  ///< GPU time of each pass (GL timestamps)
  double sceneMs = 0.0;
  double compositeMs = 0.0;
  double totalMs = 0.0;
  double wallMs = 0.0;  ///< draw call to finished frame, wall clock
};

/// Draws `world` framing `bounds` at every quality preset, cheapest first, into an offscreen
/// target of options.width x options.height, and times it. Needs the World's context current.
std::vector<RenderTiming> measureRender(const World& world, const scenes::SceneBounds& bounds,
                                        const RenderOptions& options);

}  // namespace sandphys::bench
