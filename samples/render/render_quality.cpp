#include "render/render_quality.h"

#include <array>

namespace sandphys::render {

namespace {

struct Preset {
  RenderQuality quality;
  std::string_view name;
  // The scene and composite passes cost per pixel, so the scale buys the most; the shadow map
  // costs per texel of the light's view; AO costs per pixel and sample.
  float renderScale;
  int shadowMapSize;
  int aoSamples;
};

constexpr std::array<Preset, 3> kPresets = {{
    {RenderQuality::Low, "low", 0.5f, 1024, 4},
    {RenderQuality::Medium, "medium", 0.75f, 1536, 8},
    {RenderQuality::High, "high", 1.0f, 2048, 12},
}};

const Preset& presetOf(RenderQuality quality) {
  return kPresets[static_cast<std::size_t>(quality)];
}

}  // namespace

std::string_view renderQualityName(RenderQuality quality) {
  return presetOf(quality).name;
}

std::optional<RenderQuality> parseRenderQuality(std::string_view name) {
  for (const Preset& preset : kPresets) {
    if (preset.name == name) return preset.quality;
  }
  return std::nullopt;
}

RenderQuality lowerQuality(RenderQuality quality) {
  return quality == kLowestQuality ? quality
                                   : static_cast<RenderQuality>(static_cast<int>(quality) - 1);
}

RenderQuality higherQuality(RenderQuality quality) {
  return quality == kHighestQuality ? quality
                                    : static_cast<RenderQuality>(static_cast<int>(quality) + 1);
}

void applyRenderQuality(RenderQuality quality, RenderSettings& settings) {
  const Preset& preset = presetOf(quality);
  settings.renderScale = preset.renderScale;
  settings.shadowMapSize = preset.shadowMapSize;
  settings.aoSamples = preset.aoSamples;
}

}  // namespace sandphys::render
