#include "replay/recorded_scene.h"

#include <unistd.h>

#include <string>

#include "app/progress.h"
#include "app/recording.h"
#include "support/test_world.h"

namespace sandphys::samples {

// The process id in the name: CTest runs each test in a process of its own, several at once,
// and two tests recording the same scene must not write one file.
std::filesystem::path tempRecording(const std::string& name) {
  return std::filesystem::temp_directory_path() /
         ("sandphys_replay_" + std::to_string(::getpid()) + "_" + name + ".sprec");
}

RunSummary recordScene(scenes::Scene& scene, const std::filesystem::path& file,
                       std::uint64_t frames, std::uint64_t snapshotEvery) {
  const GpuContext& gpu = testing::gpu();
  SceneRecorder recorder(file, scene, scene.settings(), kTestFrameDt, snapshotEvery,
                         gpu.description());
  ProgressLine quiet(false);
  RunHooks hooks;
  hooks.afterBuild = [&](World& world, std::uint64_t) { recorder.begin(world); };
  hooks.afterFrame = [&](World& world, std::uint64_t frame) {
    recorder.recordFrame(world, scene, static_cast<float>(kTestFrameDt), frame);
  };
  hooks.atEnd = [&](World& world, std::uint64_t) { recorder.finish(world); };
  return runScene(gpu, scene, frames, kTestFrameDt, false, quiet, hooks);
}

}  // namespace sandphys::samples
