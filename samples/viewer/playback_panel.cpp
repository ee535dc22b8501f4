#include "viewer/playback_panel.h"

#include "viewer/panel.h"

#include <imgui.h>

#include <string>

#include "viewer/panel_widgets.h"

namespace sandphys::viewer {

namespace {

const ImVec4 kWarning(1.0f, 0.8f, 0.3f, 1.0f);
const ImVec4 kError(1.0f, 0.5f, 0.3f, 1.0f);
const ImVec4 kGood(0.5f, 0.9f, 0.5f, 1.0f);

unsigned long long count(std::uint64_t value) {
  return static_cast<unsigned long long>(value);
}

void drawTimeline(const samples::Playback& playback, PlaybackRequests& requests) {
  const std::uint64_t first = 0;
  const std::uint64_t last = playback.frames();
  std::uint64_t frame = playback.busy() ? playback.target() : playback.shownFrame();
  if (ImGui::SliderScalar("timeline", ImGuiDataType_U64, &frame, &first, &last, "frame %llu")) {
    requests.scrubTo = frame;
  }
  requests.scrubbing = ImGui::IsItemActive();
  if (ImGui::IsItemHovered()) {
    ImGui::SetTooltip(
        "drag to scrub: a frame shows at once as the recorded snapshot at or before it, when\n"
        "the World has that snapshot's bodies; else it is re-simulated first");
  }
  if (playback.busy()) {
    ImGui::TextColored(kWarning, "re-simulating to frame %llu: at frame %llu",
                       count(playback.target()), count(playback.simulatedFrame()));
  } else if (playback.showingSnapshot()) {
    ImGui::TextWrapped(
        "recorded snapshot of frame %llu (re-simulated up to frame %llu); playing on "
        "re-simulates up to it",
        count(playback.shownFrame()), count(playback.simulatedFrame()));
  } else {
    ImGui::Text("re-simulated frame %llu of %llu", count(playback.shownFrame()),
                count(playback.frames()));
  }
  if (const auto& mismatch = playback.mismatch()) {
    ImGui::TextColored(kError, "differs from the recording at frame %llu:", count(mismatch->frame));
    ImGui::TextWrapped("%s", mismatch->what.c_str());
  } else {
    ImGui::TextColored(kGood, "%llu frames re-simulated, every one as recorded",
                       count(playback.checkedFrames()));
  }
}

void drawButtons(const Player& player, const PanelView& view, PlaybackRequests& requests) {
  const bool playing = !view.paused && !player.atEnd();
  if (ImGui::Button(playing ? "Pause (Space)" : "Play (Space)")) requests.togglePause = true;
  ImGui::SameLine();
  if (ImGui::Button("Step (S)")) requests.step = true;
  ImGui::SameLine();
  if (ImGui::Button("Start (R)")) requests.toStart = true;
  if (ImGui::Button("< snapshot (Left)")) requests.previousSnapshot = true;
  ImGui::SameLine();
  if (ImGui::Button("snapshot > (Right)")) requests.nextSnapshot = true;
  ImGui::SameLine();
  if (ImGui::Button("Screenshot (F)")) requests.screenshot = true;
  bool vsync = view.vsync;
  if (ImGui::Checkbox("vsync", &vsync)) requests.toggleVsync = true;
}

void drawStats(const Player& player, const FrameStats& stats, const StatsHistory& history) {
  const World& world = player.world();
  const WorldStats& s = stats.report.stats;
  const bool have = stats.report.hasStats;
  ImGui::Text("granules %u  particles %u", have ? s.granulesAlive : world.granulesSpawned(),
              world.particleCount());
  ImGui::Text("contacts %u  substeps/frame %u", have ? s.contacts : 0u, stats.report.substeps);
  ImGui::Text("step %.2f ms  render %.2f ms  frame %.2f ms", stats.stepMilliseconds,
              stats.render.totalMs, stats.frameMilliseconds);
  plots(history);
}

}  // namespace

PlaybackRequests drawPlaybackPanel(Player& player, const FrameStats& stats,
                                   const StatsHistory& history, const PanelView& view) {
  PlaybackRequests requests;
  const samples::Playback& playback = player.playback();
  const Recording& recording = playback.recording();
  ImGui::SetNextWindowPos(ImVec2(kPanelMargin, kPanelMargin), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(panelWidth(ImGui::GetIO().DisplaySize.x), 0.0f),
                           ImGuiCond_FirstUseEver);
  ImGui::Begin("sandphys (Tab hides)");
  ImGui::PushItemWidth(-120.0f);
  const std::string scene(player.scene().name());
  ImGui::Text("playing %s", scene.c_str());
  ImGui::TextWrapped("%s", player.file().string().c_str());
  const double duration = recording.frames.empty() ? 0.0 : recording.frames.back().simulatedTime;
  ImGui::TextDisabled("%llu frames, %.3f s simulated, %llu snapshots",
                      count(recording.frames.size()), duration, count(recording.snapshots.size()));
  const std::string status = player.scene().status();
  ImGui::Text("t = %.3f s  %s", player.world().simulatedTime(), status.c_str());
  drawTimeline(playback, requests);
  drawButtons(player, view, requests);
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
  const std::string* device = recording.setting("device");
  ImGui::TextWrapped("%s", view.gpu.c_str());
  if (device && *device != view.gpu) ImGui::TextWrapped("recorded on %s", device->c_str());
  ImGui::PopStyleColor();
  if (!view.lastScreenshot.empty()) ImGui::TextWrapped("saved %s", view.lastScreenshot.c_str());
  if (!view.message.empty()) ImGui::TextColored(kError, "%s", view.message.c_str());
  if (ImGui::CollapsingHeader("Rendering", ImGuiTreeNodeFlags_DefaultOpen)) {
    renderQualityCombo(player.pacer());
    renderTimes(stats.render);
  }
  if (ImGui::CollapsingHeader("Statistics", ImGuiTreeNodeFlags_DefaultOpen)) {
    drawStats(player, stats, history);
  }
  if (ImGui::CollapsingHeader("Controls")) {
    ImGui::TextUnformatted(
        "left drag: orbit    middle or Shift+left drag: pan\n"
        "wheel: zoom\n"
        "Space: play or pause    S: step one frame    R: back to the start\n"
        "Left, Right: the recorded snapshot before or after\n"
        "Esc: quit");
    ImGui::TextUnformatted(view.panelInScreenshots
                               ? "F: screenshot of the window, panel included"
                               : "F: screenshot of the scene (no panel; --panel-in-screenshots)");
  }
  ImGui::PopItemWidth();
  ImGui::End();
  return requests;
}

}  // namespace sandphys::viewer
