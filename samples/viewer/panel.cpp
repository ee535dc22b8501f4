#include "viewer/panel.h"

#include <imgui.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>

#include "sandphys/settings_fields.h"
#include "scenes/scene_parameters.h"

#include "viewer/panel_widgets.h"

namespace sandphys::viewer {

namespace {

// A control of a WorldSettings field: named and explained as the library's table states it.
std::string settingLabel(std::string_view key) {
  const SettingField& field = *findWorldSettingField(key);
  return *field.unit ? std::string(field.label) + ", " + field.unit : std::string(field.label);
}
void settingTooltip(std::string_view key) {
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", findWorldSettingField(key)->help);
}

template <typename T>
void clampTo(T& value, double min, double max) {
  value = static_cast<T>(std::clamp(static_cast<double>(value), min, max));
}

// Edits one scene parameter in place; true when the value changed.
bool editParameter(const scenes::SceneParameter& parameter) {
  const char* label = parameter.name.c_str();
  bool changed = false;
  std::visit(
      [&](auto* value) {
        using T = std::remove_pointer_t<decltype(value)>;
        if constexpr (std::is_same_v<T, std::uint32_t>) {
          changed = ImGui::InputScalar(label, ImGuiDataType_U32, value);
          clampTo(*value, parameter.min, parameter.max);
        } else if constexpr (std::is_same_v<T, std::uint64_t>) {
          changed = ImGui::InputScalar(label, ImGuiDataType_U64, value);
          clampTo(*value, parameter.min, parameter.max);
        } else if constexpr (std::is_same_v<T, float>) {
          changed = ImGui::InputFloat(label, value, 0.0f, 0.0f, "%.4g");
          clampTo(*value, parameter.min, parameter.max);
        } else if constexpr (std::is_same_v<T, std::string>) {
          // A file name: edited as text, taken when the user presses Enter.
          char buffer[1024];
          std::snprintf(buffer, sizeof buffer, "%s", value->c_str());
          if (ImGui::InputText(label, buffer, sizeof buffer,
                               ImGuiInputTextFlags_EnterReturnsTrue) &&
              buffer[0] != '\0') {
            *value = buffer;
            changed = true;
          }
        } else {
          changed = ImGui::InputScalarN(label, ImGuiDataType_U32, value->data(), 3);
          for (std::uint32_t& count : *value) clampTo(count, parameter.min, parameter.max);
        }
      },
      parameter.value);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", parameter.help.c_str());
  return changed;
}

}  // namespace

PanelRequests Panel::draw(Session& session, const FrameStats& stats, const StatsHistory& history,
                          const PanelView& view) {
  PanelRequests requests;
  const float windowWidth = ImGui::GetIO().DisplaySize.x;
  ImGui::SetNextWindowPos(ImVec2(kPanelMargin, kPanelMargin), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(panelWidth(windowWidth), 0.0f), ImGuiCond_FirstUseEver);
  ImGui::Begin("sandphys (Tab hides)");
  // Fields leave room on their right for labels as long as "Young's modulus, Pa".
  ImGui::PushItemWidth(-0.4f * ImGui::GetWindowWidth());
  drawScene(session, view, requests);
  // The scene, its state and the buttons show; every section below opens on a click.
  if (ImGui::CollapsingHeader("Pacing and rendering")) drawPacing(session, stats);
  if (ImGui::CollapsingHeader("Scene parameters")) drawParameters(session);
  if (ImGui::CollapsingHeader("Material and time step")) drawControls(session);
  if (ImGui::CollapsingHeader("Statistics")) drawStats(session, stats, history);
  if (ImGui::CollapsingHeader("Controls")) drawHelp(view);
  ImGui::PopItemWidth();
  ImGui::End();
  return requests;
}

void Panel::drawScene(Session& session, const PanelView& view, PanelRequests& requests) {
  const std::string_view current = session.scene().name();
  if (ImGui::BeginCombo("scene", std::string(current).c_str())) {
    std::string_view category;
    for (const scenes::SceneEntry& entry : scenes::sceneRegistry()) {
      if (entry.category != category) {
        category = entry.category;
        ImGui::TextDisabled("%.*s", static_cast<int>(category.size()), category.data());
      }
      const std::string name(entry.name);
      if (ImGui::Selectable(("  " + name).c_str(), entry.name == current)) {
        requests.switchTo = &entry;
      }
      if (ImGui::IsItemHovered()) {
        ImGui::SetTooltip("%.*s", static_cast<int>(entry.description.size()),
                          entry.description.data());
      }
    }
    ImGui::EndCombo();
  }
  const std::string status = session.scene().status();
  ImGui::Text("t = %.3f s  %s", session.world().simulatedTime(), status.c_str());

  // Two buttons a row: the panel opens a quarter of the window wide.
  if (ImGui::Button(view.paused ? "Run (Space)" : "Pause (Space)")) requests.togglePause = true;
  ImGui::SameLine();
  if (ImGui::Button("Step (S)")) requests.step = true;
  if (ImGui::Button("Restart (R)")) requests.restart = true;
  ImGui::SameLine();
  if (ImGui::Button("Screenshot (F)")) requests.screenshot = true;
  bool vsync = view.vsync;
  if (ImGui::Checkbox("vsync", &vsync)) requests.toggleVsync = true;
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
  ImGui::TextWrapped("%s", view.gpu.c_str());
  ImGui::PopStyleColor();
  if (!view.lastScreenshot.empty()) ImGui::TextWrapped("saved %s", view.lastScreenshot.c_str());
  if (!view.message.empty()) {
    ImGui::TextColored(ImVec4(1.0f, 0.5f, 0.3f, 1.0f), "%s", view.message.c_str());
  }
}

void Panel::drawPacing(Session& session, const FrameStats& stats) {
  FramePacer& pacer = session.pacer();
  float budget = static_cast<float>(pacer.budgetMs());
  // The slider's end is a practical one; Ctrl+click types any budget in.
  if (ImGui::SliderFloat("frame budget", &budget, 0.0f, 250.0f,
                         budget > 0.0f ? "%.0f ms" : "off")) {
    pacer.setBudgetMs(std::max(budget, 0.0f));
  }
  if (ImGui::IsItemHovered()) {
    ImGui::SetTooltip(
        "wall-clock time a frame may take: each frame runs the substeps that fit beside the\n"
        "rendering (slow motion when fewer than a frame dt needs); off: every frame simulates\n"
        "its whole frame dt however long that takes");
  }

  renderQualityCombo(pacer);
  renderTimes(stats.render);
  if (!stats.stepped) {
    ImGui::TextDisabled("paused: no substeps this frame");
  } else if (stats.slowMotion) {
    ImGui::TextColored(ImVec4(1.0f, 0.8f, 0.3f, 1.0f), "slow motion x%.3g, %u of %u substeps",
                       stats.timeScale, stats.report.substeps, stats.fullSubsteps);
  } else {
    ImGui::Text("real time, %u of %u substeps", stats.report.substeps, stats.fullSubsteps);
  }
  ImGui::Text("step %.2f ms per substep (smoothed)", pacer.msPerSubstep());
}

void Panel::drawParameters(Session& session) {
  scenes::Scene& scene = session.scene();
  ImGui::TextDisabled("applied on restart (R)");
  for (const scenes::SceneParameter& parameter : scene.parameters()) {
    const std::string before = scenes::formatSceneParameter(parameter);
    if (!editParameter(parameter)) continue;
    // The scene checks its parameters together (capacity limits, a batch inside its
    // container); a value it refuses is put back, so that Restart always works.
    try {
      (void)scene.settings();
      m_parameterError.clear();
    } catch (const Error& error) {
      m_parameterError = error.what();
      scenes::setSceneParameter(scene, parameter.name, before);
    }
  }
  if (!m_parameterError.empty()) {
    ImGui::TextColored(ImVec4(1.0f, 0.5f, 0.3f, 1.0f), "refused: %s", m_parameterError.c_str());
  }
}

void Panel::drawControls(Session& session) {
  SimulationControls& controls = session.controls();
  const SimulationControls& applied = session.applied();
  const bool pending = controls.youngsModulus != applied.youngsModulus ||
                       controls.friction != applied.friction ||
                       controls.restitution != applied.restitution ||
                       controls.stepsPerContact != applied.stepsPerContact ||
                       controls.frameDt != applied.frameDt || controls.sleep != applied.sleep;
  if (pending) {
    ImGui::TextColored(ImVec4(1.0f, 0.8f, 0.3f, 1.0f), "changed: applied on restart (R)");
  } else {
    ImGui::TextDisabled("applied on restart (R)");
  }
  if (ImGui::InputFloat(settingLabel("youngs_modulus").c_str(), &controls.youngsModulus, 0.0f, 0.0f,
                        "%.3g")) {
    clampTo(controls.youngsModulus, 1.0e3, 1.0e11);
  }
  settingTooltip("youngs_modulus");
  ImGui::SliderFloat(settingLabel("friction").c_str(), &controls.friction, 0.0f, 1.5f, "%.2f");
  settingTooltip("friction");
  ImGui::SliderFloat(settingLabel("restitution").c_str(), &controls.restitution, 0.05f, 1.0f,
                     "%.2f");
  settingTooltip("restitution");
  ImGui::SliderFloat(settingLabel("steps_per_contact").c_str(), &controls.stepsPerContact,
                     kMinStepsPerContact, 100.0f, "%.0f");
  settingTooltip("steps_per_contact");
  float frameMs = static_cast<float>(controls.frameDt * 1e3);
  if (ImGui::SliderFloat("frame dt, ms", &frameMs, 1.0f, 50.0f, "%.2f")) {
    controls.frameDt = frameMs * 1e-3;
  }
  ImGui::Checkbox(settingLabel("sleep").c_str(), &controls.sleep);
  settingTooltip("sleep");
  ImGui::SameLine();
  ImGui::Checkbox("tint sleeping", &controls.tintSleeping);
  ImGui::Checkbox("bodies as particles", &controls.bodyParticles);
  if (ImGui::IsItemHovered()) {
    ImGui::SetTooltip("draw the bodies (blocks, rocks, tools) as the particles the sand touches");
  }
  ImGui::Checkbox(settingLabel("profile_kernels").c_str(), &controls.profileKernels);
  settingTooltip("profile_kernels");
  if (!session.lastError().empty()) {
    ImGui::TextColored(ImVec4(1.0f, 0.5f, 0.3f, 1.0f), "refused, scene defaults used: %s",
                       session.lastError().c_str());
  }
}

void Panel::drawStats(const Session& session, const FrameStats& stats,
                      const StatsHistory& history) {
  const World& world = session.world();
  const ContactModel& model = world.contactModel();
  const WorldStats& s = stats.report.stats;
  const bool have = stats.report.hasStats;
  ImGui::Text("granules %u  particles %u", have ? s.granulesAlive : world.granulesSpawned(),
              stats.particles);
  if (world.sleepModel().enabled && have) {
    // Idle: substeps of this frame skipped because all the sand slept (StepReport::idleSubsteps).
    ImGui::Text("awake %u  asleep %u  idle substeps %u", s.granulesAlive - s.granulesAsleep,
                s.granulesAsleep, stats.report.idleSubsteps);
  }
  ImGui::Text("contacts %u  substeps/frame %u", have ? s.contacts : 0u, stats.report.substeps);
  ImGui::Text("dt %.3g s = %.3f t_n  (t_n %.3g s)", static_cast<double>(model.timeStep),
              static_cast<double>(model.timeStep / model.contactTime),
              static_cast<double>(model.contactTime));
  ImGui::Text("Cundall %.3g granule steps/s", stats.cundall);
  // %.3g: in slow motion on a CPU the ratio is a few 1e-4, which %.3f would show as 0.
  ImGui::Text("simulated / wall %.3g", stats.simPerWall);
  if (model.law == ContactLaw::PaperViscous) {
    ImGui::Text("paper's law: max overlap %.4f d  (capped at 0.1 d)", stats.maxOverlapOverD);
    ImGui::Text("guards: penetration %llu  velocity %llu",
                static_cast<unsigned long long>(s.penetrationClamps),
                static_cast<unsigned long long>(s.velocityClamps));
  } else {
    ImGui::Text("Hertz-Mindlin: max overlap %.4f d  (no cap)", stats.maxOverlapOverD);
    ImGui::Text("contacts without a slot %llu  velocity guard %llu",
                static_cast<unsigned long long>(s.contactSlotOverflows),
                static_cast<unsigned long long>(s.velocityClamps));
  }
  ImGui::Text("dropped %.3f s%s", stats.droppedSeconds,
              stats.report.emitterBlocked ? "  emitter blocked (capacity)" : "");
  ImGui::Text("poured %u of %u", session.tools().poured(), SandTools::kPourGranules);
  if (s.granulesNotBorn > 0) {
    ImGui::Text("emitted granules not born (place taken) %u", s.granulesNotBorn);
  }
  if (session.recording()) {
    ImGui::Text("recording: %llu frames (ends at a restart)",
                static_cast<unsigned long long>(session.recordedFrames()));
  }
  ImGui::Text("step %.2f ms  render %.2f ms  frame %.2f ms", stats.stepMilliseconds,
              stats.render.totalMs, stats.frameMilliseconds);
  if (stats.kernels.empty()) {
    ImGui::TextDisabled("kernel times: tick 'profile kernels'");
  } else if (ImGui::TreeNode("kernels")) {
    double total = 0.0;
    for (const KernelTime& kernel : stats.kernels) {
      ImGui::Text("%-22s %7.3f ms  x%u", kernel.name.c_str(), kernel.milliseconds,
                  kernel.dispatches);
      total += kernel.milliseconds;
    }
    ImGui::Text("%-22s %7.3f ms", "total", total);
    ImGui::TreePop();
  }
  plots(history);
}

void Panel::drawHelp(const PanelView& view) {
  ImGui::TextUnformatted(
      "left drag: orbit    middle or Shift+left drag: pan\n"
      "wheel: zoom\n"
      "right button or P held: pour sand under the cursor\n"
      "Ctrl+left button or B held: push sand with a sphere\n"
      "Space: pause    S: step    R: restart    Esc: quit    Home: the scene's view    Tab: "
      "hide the panel");
  ImGui::TextUnformatted(view.panelInScreenshots
                             ? "F: screenshot of the window, panel included"
                             : "F: screenshot of the scene (no panel; --panel-in-screenshots)");
}

}  // namespace sandphys::viewer
