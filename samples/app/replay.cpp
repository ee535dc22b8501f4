// --replay: the scene of a recording rebuilt from its settings and re-simulated frame by frame,
// every frame checked against what was recorded.
#include "app/replay.h"

#include <chrono>
#include <cstdio>
#include <cstring>

#include "app/cli.h"
#include "scenes/registry.h"
#include "scenes/scene_parameters.h"

namespace sandphys::samples {

namespace {

using Clock = std::chrono::steady_clock;

std::string hashText(std::uint64_t hash) {
  char text[32];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash));
  return text;
}

const WorldSnapshot* snapshotFrom(const Recording& recording, std::uint64_t frame) {
  for (const WorldSnapshot& snapshot : recording.snapshots) {
    if (snapshot.frame >= frame) return &snapshot;
  }
  return nullptr;
}

}  // namespace

const WorldSnapshot* snapshotAt(const Recording& recording, std::uint64_t frame) {
  for (const WorldSnapshot& snapshot : recording.snapshots) {
    if (snapshot.frame == frame) return &snapshot;
  }
  return nullptr;
}

std::unique_ptr<scenes::Scene> sceneFromRecording(const Recording& recording) {
  const std::string name = "recording '" + recording.file.string() + "'";
  const std::string* sceneName = recording.setting("scene");
  if (!sceneName) throw RecordingError(name + " names no scene");
  const scenes::SceneEntry* entry = scenes::findScene(*sceneName);
  if (!entry) {
    throw RecordingError(name + " is of scene '" + *sceneName +
                         "', which this build does not have (see --list)");
  }
  std::unique_ptr<scenes::Scene> scene = entry->create();
  const std::size_t prefix = std::strlen(kParameterPrefix);
  for (const auto& [key, value] : recording.settings) {
    if (key.compare(0, prefix, kParameterPrefix) != 0) continue;
    try {
      scenes::setSceneParameter(*scene, key.substr(prefix), value);
    } catch (const Error& error) {
      throw RecordingError(name + ": this build refuses its setting " + key + " = " + value + ": " +
                           error.what());
    }
  }
  try {
    (void)scene->settings();
  } catch (const Error& error) {
    throw RecordingError(name + ": this build refuses its scene's settings: " + error.what());
  }
  return scene;
}

ReplayRun::ReplayRun(const GpuContext& gpu, const Recording& recording)
    : m_recording(recording), m_scene(sceneFromRecording(recording)) {
  // The World checks its settings against this build's limits (and the GPU's).
  try {
    m_world.emplace(gpu, worldSettingsFrom(recording, m_scene->settings()));
    m_scene->build(*m_world);
  } catch (const GpuError&) {
    throw;
  } catch (const RecordingError&) {
    throw;
  } catch (const Error& error) {
    throw RecordingError("recording '" + recording.file.string() +
                         "': this build refuses the World it records: " + error.what());
  }
  if (const std::string* used = recording.setting(kToolsKey)) {
    if (*used != kSandTools) {
      throw RecordingError("recording '" + recording.file.string() +
                           "': this build refuses its setting tools = " + *used);
    }
    m_tools.emplace();
    m_tools->attach(*m_world, *m_scene);
  }
}

StepReport ReplayRun::stepFrame() {
  const std::uint64_t frame = m_frame + 1;
  const RecordedFrame& recorded = m_recording.frames.at(frame - 1);
  // The tools' input first, then the scene: the order the recorded run had.
  if (m_tools) {
    const ToolInput input = readToolEvents(m_recording, frame);
    m_tools->update(*m_world, input.pour, input.push, input.cursor, recorded.frameDt);
  } else if (!recorded.events.empty()) {
    throw RecordingError("recording '" + m_recording.file.string() + "': frame " +
                         std::to_string(frame) + " has events but the run had no tools");
  }
  const StepReport report = m_scene->step(*m_world, recorded.frameDt);
  if (m_tools) m_tools->countEmitted(report.granulesEmitted);
  m_scene->update(*m_world, report, m_world->simulatedTime());
  m_frame = frame;
  return report;
}

std::optional<std::string> ReplayRun::compareWith(const WorldSnapshot& snapshot) const {
  const WorldSnapshot replayed = m_world->readSnapshot();
  if (const std::optional<StateDifference> d = firstDifference(snapshot, replayed)) {
    return d->describe();
  }
  return std::nullopt;
}

std::optional<ReplayRun::Difference> ReplayRun::checkFrame() {
  const WorldSnapshot* snapshot = snapshotAt(m_recording, m_frame);
  if (m_frame == 0) {
    if (!snapshot) return std::nullopt;
    if (auto d = compareWith(*snapshot)) return Difference{"state after build: " + *d};
    return std::nullopt;
  }
  const RecordedFrame& recorded = m_recording.frames.at(m_frame - 1);
  const std::string at = "frame " + std::to_string(m_frame) + ": ";
  if (m_world->stepCount() != recorded.steps ||
      m_world->simulatedTime() != recorded.simulatedTime) {
    return Difference{at + "substeps run in all: recorded " + std::to_string(recorded.steps) +
                      ", replayed " + std::to_string(m_world->stepCount())};
  }
  const std::vector<RecordedInput> inputs = m_scene->externalInputs();
  if (inputs.size() != recorded.inputs.size()) {
    return Difference{at + "external inputs: recorded " + std::to_string(recorded.inputs.size()) +
                      ", replayed " + std::to_string(inputs.size())};
  }
  for (std::size_t k = 0; k < inputs.size(); ++k) {
    if (const auto d = firstDifference(recorded.inputs[k], inputs[k])) {
      return Difference{at + "external input " + std::to_string(k) + ", " + d->describe()};
    }
  }
  const std::uint64_t hash = m_world->readStateHash();
  if (hash != recorded.stateHash) {
    std::string what =
        at + "state hash recorded " + hashText(recorded.stateHash) + ", replayed " + hashText(hash);
    if (!snapshot) return Difference{what, true};
    if (auto d = compareWith(*snapshot)) what += "; " + *d;
    return Difference{what};
  }
  if (snapshot) {
    if (auto d = compareWith(*snapshot)) return Difference{at + *d};
  }
  return std::nullopt;
}

std::string deviceCaveat(const GpuContext& gpu, const Recording& recording) {
  const std::string* device = recording.setting("device");
  if (!device || *device == gpu.description()) return {};
  return " (recorded on " + *device + ", replayed on " + gpu.description() +
         ": replays are bit-identical on the same device and driver only)";
}

ReplayResult replayRecording(const GpuContext& gpu, const Recording& recording,
                             const ReplayHook& afterFrame) {
  ReplayRun run(gpu, recording);
  ReplayResult result;
  auto differ = [&](std::uint64_t frame, std::string what) {
    result.identical = false;
    result.firstDifferentFrame = frame;
    result.difference = std::move(what) + deviceCaveat(gpu, recording);
    return result;
  };

  if (auto d = run.checkFrame()) return differ(0, d->what);
  const Clock::time_point start = Clock::now();
  while (run.frame() < recording.frames.size()) {
    run.stepFrame();
    const std::uint64_t frame = run.frame();
    if (afterFrame) afterFrame(run.world(), frame);
    result.frames = frame;
    std::optional<ReplayRun::Difference> d = run.checkFrame();
    if (!d) continue;
    if (d->hashOnly) {
      // The values of this frame were not kept: run on to the next snapshot and compare there.
      if (const WorldSnapshot* next = snapshotFrom(recording, frame)) {
        while (run.frame() < next->frame) run.stepFrame();
        d->what += "; at the next snapshot (frame " + std::to_string(next->frame) + ") ";
        const std::optional<std::string> there = run.compareWith(*next);
        d->what += there ? *there
                         : "the states agree again (the difference died out; record with "
                           "--snapshot-every 1 to see it)";
      }
    }
    return differ(frame, d->what);
  }
  result.wallSeconds = std::chrono::duration<double>(Clock::now() - start).count();
  return result;
}

int runReplay(const std::filesystem::path& file, bool quiet) {
  const Recording recording = readRecording(file);
  const GpuContext gpu = GpuContext::headless();
  const ReplayResult result = replayRecording(gpu, recording);
  const std::string* scene = recording.setting("scene");
  if (!result.identical) {
    std::fprintf(stderr, "sandphys-samples: replay of '%s' (%s) differs at %s\n",
                 file.string().c_str(), scene ? scene->c_str() : "?", result.difference.c_str());
    return kExitFailure;
  }
  if (!quiet) {
    std::fprintf(stderr,
                 "sandphys-samples: replay of '%s' (%s): %llu frames bit-identical (%zu "
                 "snapshots compared); %.2f s wall, recorded run %.2f s (%.2fx)\n",
                 file.string().c_str(), scene ? scene->c_str() : "?",
                 static_cast<unsigned long long>(result.frames), recording.snapshots.size(),
                 result.wallSeconds, recording.wallSeconds,
                 recording.wallSeconds > 0.0 ? result.wallSeconds / recording.wallSeconds : 0.0);
  }
  return kExitOk;
}

}  // namespace sandphys::samples
