#include "viewer/panel_widgets.h"

#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <optional>
#include <string>

#include "render/render_quality.h"

namespace sandphys::viewer {

namespace {

void plot(const char* label, const PlotHistory& history, const char* format) {
  char overlay[64];
  std::snprintf(overlay, sizeof overlay, format, static_cast<double>(history.latest()));
  ImGui::PlotLines(label, history.data(), history.size(), 0, overlay, 0.0f,
                   std::max(history.max() * 1.1f, 1e-12f), ImVec2(0.0f, 48.0f));
}

}  // namespace

void renderQualityCombo(FramePacer& pacer) {
  const std::optional<render::RenderQuality> fixed = pacer.fixedQuality();
  const std::string effective(render::renderQualityName(pacer.quality()));
  const std::string preview = fixed ? effective : "auto: " + effective;
  if (ImGui::BeginCombo("render quality", preview.c_str())) {
    if (ImGui::Selectable("auto", !fixed)) pacer.setFixedQuality(std::nullopt);
    for (render::RenderQuality quality = render::kLowestQuality;;
         quality = render::higherQuality(quality)) {
      const std::string name(render::renderQualityName(quality));
      if (ImGui::Selectable(name.c_str(), fixed == quality)) pacer.setFixedQuality(quality);
      if (quality == render::kHighestQuality) break;
    }
    ImGui::EndCombo();
  }
  if (ImGui::IsItemHovered()) {
    ImGui::SetTooltip(
        "render scale, shadow map and AO samples; auto lowers the preset when rendering takes\n"
        "over half the frame budget, and raises it when rendering takes well under it");
  }
}

void renderTimes(const render::RenderStats& render) {
  ImGui::Text("render %dx%d: %.1f ms GPU", render.renderWidth, render.renderHeight, render.totalMs);
  ImGui::Text("  shadow %.1f + scene %.1f + composite %.1f ms", render.shadowMs, render.sceneMs,
              render.compositeMs);
}

void plots(const StatsHistory& history) {
  plot("kinetic energy", history.kineticEnergy, "%.3g J");
  plot("contacts", history.contacts, "%.0f");
  plot("frame", history.frameMs, "%.1f ms");
}

}  // namespace sandphys::viewer
