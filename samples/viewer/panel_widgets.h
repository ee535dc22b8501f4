#pragma once

#include "render/renderer.h"
#include "viewer/frame_pacer.h"
#include "viewer/frame_stats.h"

namespace sandphys::viewer {

/// Dear ImGui pieces that the live panel and the playback panel share; each draws into the
/// current window.

/// The render quality preset: auto or one fixed, applied from the next frame.
void renderQualityCombo(FramePacer& pacer);
/// The renderer's size and GPU time per pass.
void renderTimes(const render::RenderStats& render);
/// The live plots: kinetic energy, contacts, frame time.
void plots(const StatsHistory& history);

}  // namespace sandphys::viewer
