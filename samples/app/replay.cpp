// --replay: the scene of a recording rebuilt from its settings and re-simulated frame by frame,
// every frame checked against what was recorded.
#include "app/replay.h"

#include <chrono>
#include <cstdio>
#include <cstring>

#include "app/cli.h"
#include "scenes/registry.h"

namespace sandphys::samples {

namespace {

using Clock = std::chrono::steady_clock;

std::string hashText(std::uint64_t hash) {
  char text[32];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash));
  return text;
}

const WorldSnapshot* snapshotAt(const Recording& recording, std::uint64_t frame) {
  for (const WorldSnapshot& snapshot : recording.snapshots) {
    if (snapshot.frame == frame) return &snapshot;
  }
  return nullptr;
}

const WorldSnapshot* snapshotFrom(const Recording& recording, std::uint64_t frame) {
  for (const WorldSnapshot& snapshot : recording.snapshots) {
    if (snapshot.frame >= frame) return &snapshot;
  }
  return nullptr;
}

}  // namespace

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

ReplayResult replayRecording(const GpuContext& gpu, const Recording& recording,
                             const ReplayHook& afterFrame) {
  std::unique_ptr<scenes::Scene> scene = sceneFromRecording(recording);
  ReplayResult result;
  // The World checks its settings against this build's limits (and the GPU's).
  std::optional<World> made;
  try {
    made.emplace(gpu, worldSettingsFrom(recording, scene->settings()));
    scene->build(*made);
  } catch (const GpuError&) {
    throw;
  } catch (const RecordingError&) {
    throw;
  } catch (const Error& error) {
    throw RecordingError("recording '" + recording.file.string() +
                         "': this build refuses the World it records: " + error.what());
  }
  World& world = *made;
  std::optional<scenes::SandTools> tools;
  if (const std::string* used = recording.setting(kToolsKey)) {
    if (*used != kSandTools) {
      throw RecordingError("recording '" + recording.file.string() +
                           "': this build refuses its setting tools = " + *used);
    }
    tools.emplace();
    tools->attach(world, *scene);
  }
  // One frame as the recorded run stepped it: the tools' input first, then the scene.
  auto stepFrame = [&](std::uint64_t frame) {
    const RecordedFrame& recorded = recording.frames[frame - 1];
    if (tools) {
      const ToolInput input = readToolEvents(recording, frame);
      tools->update(world, input.pour, input.push, input.cursor, recorded.frameDt);
    } else if (!recorded.events.empty()) {
      throw RecordingError("recording '" + recording.file.string() + "': frame " +
                           std::to_string(frame) + " has events but the run had no tools");
    }
    const StepReport report = scene->step(world, recorded.frameDt);
    if (tools) tools->countEmitted(report.granulesEmitted);
    scene->update(world, report, world.simulatedTime());
  };

  auto differ = [&](std::uint64_t frame, std::string what) {
    result.identical = false;
    result.firstDifferentFrame = frame;
    result.difference = std::move(what);
    const std::string* device = recording.setting("device");
    if (device && *device != gpu.description()) {
      result.difference += " (recorded on " + *device + ", replayed on " + gpu.description() +
                           ": replays are bit-identical on the same device and driver only)";
    }
    return result;
  };
  auto compareSnapshot = [&](const WorldSnapshot& recorded) -> std::optional<std::string> {
    const WorldSnapshot replayed = world.readSnapshot();
    if (const std::optional<StateDifference> d = firstDifference(recorded, replayed)) {
      return d->describe();
    }
    return std::nullopt;
  };

  if (const WorldSnapshot* initial = snapshotAt(recording, 0)) {
    if (auto d = compareSnapshot(*initial)) return differ(0, "state after build: " + *d);
  }
  const Clock::time_point start = Clock::now();
  for (std::uint64_t i = 0; i < recording.frames.size(); ++i) {
    const RecordedFrame& recorded = recording.frames[i];
    const std::uint64_t frame = i + 1;
    stepFrame(frame);
    if (afterFrame) afterFrame(world, frame);
    result.frames = frame;
    const std::string at = "frame " + std::to_string(frame) + ": ";
    if (world.stepCount() != recorded.steps || world.simulatedTime() != recorded.simulatedTime) {
      return differ(frame, at + "substeps run in all: recorded " + std::to_string(recorded.steps) +
                               ", replayed " + std::to_string(world.stepCount()));
    }
    const std::vector<RecordedInput> inputs = scene->externalInputs();
    if (inputs.size() != recorded.inputs.size()) {
      return differ(frame, at + "external inputs: recorded " +
                               std::to_string(recorded.inputs.size()) + ", replayed " +
                               std::to_string(inputs.size()));
    }
    for (std::size_t k = 0; k < inputs.size(); ++k) {
      if (const auto d = firstDifference(recorded.inputs[k], inputs[k])) {
        return differ(frame, at + "external input " + std::to_string(k) + ", " + d->describe());
      }
    }
    const std::uint64_t hash = world.readStateHash();
    const WorldSnapshot* snapshot = snapshotAt(recording, frame);
    if (hash != recorded.stateHash) {
      std::string what = at + "state hash recorded " + hashText(recorded.stateHash) +
                         ", replayed " + hashText(hash);
      if (snapshot) {
        if (auto d = compareSnapshot(*snapshot)) what += "; " + *d;
        return differ(frame, what);
      }
      // The values of this frame were not kept: run on to the next snapshot and compare there.
      if (const WorldSnapshot* next = snapshotFrom(recording, frame)) {
        for (std::uint64_t j = frame + 1; j <= next->frame; ++j) stepFrame(j);
        what += "; at the next snapshot (frame " + std::to_string(next->frame) + ") ";
        const std::optional<std::string> d = compareSnapshot(*next);
        what += d ? *d
                  : "the states agree again (the difference died out; record with "
                    "--snapshot-every 1 to see it)";
      }
      return differ(frame, what);
    }
    if (snapshot) {
      if (auto d = compareSnapshot(*snapshot)) return differ(frame, at + *d);
    }
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
