#pragma once

#include <cstdint>
#include <optional>

#include "viewer/frame_stats.h"
#include "viewer/panel.h"
#include "viewer/player.h"

namespace sandphys::viewer {

/// What the user asked for in the playback panel this frame; the viewer applies it after the
/// frame.
struct PlaybackRequests {
  std::optional<std::uint64_t> scrubTo;  ///< the timeline was moved to this frame
  bool scrubbing = false;                ///< the timeline is held: playing waits meanwhile
  bool togglePause = false;
  bool step = false;
  bool toStart = false;
  bool previousSnapshot = false;
  bool nextSnapshot = false;
  bool screenshot = false;
  bool toggleVsync = false;
};

/// The Dear ImGui panel of --play: the recording, its timeline, whether every frame re-simulated
/// matches it, the playing controls, render quality and statistics.
PlaybackRequests drawPlaybackPanel(Player& player, const FrameStats& stats,
                                   const StatsHistory& history, const PanelView& view);

}  // namespace sandphys::viewer
