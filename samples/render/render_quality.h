#pragma once

#include <optional>
#include <string_view>

#include "render/renderer.h"

namespace sandphys::render {

/// Cost presets of the renderer, from cheapest to best looking. Each one sets only what the
/// frame's cost depends on (render scale, shadow-map size, ambient-occlusion samples); the light
/// and colours stay as they are.
enum class RenderQuality { Low, Medium, High };

inline constexpr RenderQuality kLowestQuality = RenderQuality::Low;
inline constexpr RenderQuality kHighestQuality = RenderQuality::High;

/// "low", "medium" or "high".
std::string_view renderQualityName(RenderQuality quality);
/// The preset named `name` (as renderQualityName spells it), or nothing.
std::optional<RenderQuality> parseRenderQuality(std::string_view name);
/// One step cheaper or dearer, saturating at the ends.
RenderQuality lowerQuality(RenderQuality quality);
RenderQuality higherQuality(RenderQuality quality);

/// Puts the preset's render scale, shadow-map size and AO sample count into `settings`.
void applyRenderQuality(RenderQuality quality, RenderSettings& settings);

}  // namespace sandphys::render
