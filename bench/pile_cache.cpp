#include "pile_cache.h"

#include <cstdio>
#include <functional>

#include <nlohmann/json.hpp>

#include "report.h"

namespace sandphys::bench {

namespace {

// Recording settings of a settled pile's file.
constexpr const char* kKeySetting = "settled_pile";
constexpr const char* kSettleSetting = "settle_substeps";
constexpr const char* kSleepWaitSetting = "sleep_wait_substeps";
constexpr const char* kPeakOverlapSetting = "peak_overlap_d";

// A double as text that reads back to the same value.
std::string exact(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

}  // namespace

std::string settledPileKey(const MeasureOptions& options, const SizePlan& plan, World& world) {
  nlohmann::json key = {{"pile", pileJson(options)["options"]},
                        {"granules", plan.granules},
                        {"settle_substeps", plan.settleSteps},
                        {"sleep", options.sleep},
                        {"sleep_wait_factor", options.sleepWaitFactor},
                        {"built_state_hash", hex(world.readStateHash())}};
  // Only when it sorts, so that the keys of the piles settled without sorts stay; a shuffled
  // pile differs in its built state.
  if (const std::uint32_t interval = granuleSortInterval(world.settings()); interval > 0) {
    key["sort_interval"] = interval;
  }
  return key.dump();
}

std::filesystem::path settledPileFile(const std::string& folder, const MeasureOptions& options,
                                      std::uint32_t granules, const std::string& key) {
  const std::string name = std::string(benchSceneName(options.scene)) + "-" +
                           std::to_string(granules) + "-" + hex(std::hash<std::string>{}(key)) +
                           ".sprec";
  return std::filesystem::path(folder) / name;
}

std::optional<SettledPile> loadSettledPile(const std::filesystem::path& file,
                                           const std::string& key, World& world) {
  std::error_code error;
  if (!std::filesystem::exists(file, error)) return std::nullopt;
  try {
    const Recording recording = readRecording(file);
    const std::string* written = recording.setting(kKeySetting);
    const std::string* settle = recording.setting(kSettleSetting);
    const std::string* sleepWait = recording.setting(kSleepWaitSetting);
    const std::string* peakOverlap = recording.setting(kPeakOverlapSetting);
    if (!written || *written != key || !settle || !sleepWait || !peakOverlap ||
        recording.snapshots.size() != 1) {
      std::fprintf(stderr, "sandphys-bench: %s holds another pile; settling this one\n",
                   file.string().c_str());
      return std::nullopt;
    }
    SettledPile pile;
    pile.settleSteps = std::uint32_t(std::stoul(*settle));
    pile.sleepWaitSteps = std::uint32_t(std::stoul(*sleepWait));
    pile.peakOverlap = std::stod(*peakOverlap);
    pile.settleWallSeconds = recording.wallSeconds;
    world.restoreSnapshot(recording.snapshots.front());
    return pile;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sandphys-bench: cannot use the settled pile %s (%s); settling again\n",
                 file.string().c_str(), e.what());
    return std::nullopt;
  }
}

void saveSettledPile(const std::filesystem::path& file, const std::string& key,
                     const SettledPile& pile, World& world) {
  std::error_code error;
  std::filesystem::create_directories(file.parent_path(), error);
  if (error) {
    throw Error("--pile-cache: cannot create '" + file.parent_path().string() +
                "': " + error.message());
  }
  std::filesystem::path part = file;
  part += ".part";
  {
    RecordingWriter writer(part, {{kKeySetting, key},
                                  {kSettleSetting, std::to_string(pile.settleSteps)},
                                  {kSleepWaitSetting, std::to_string(pile.sleepWaitSteps)},
                                  {kPeakOverlapSetting, exact(pile.peakOverlap)}});
    writer.addSnapshot(world.readSnapshot());
    writer.finish(pile.settleWallSeconds);
  }
  std::filesystem::rename(part, file, error);
  if (error) {
    throw Error("--pile-cache: cannot write '" + file.string() + "': " + error.message());
  }
}

}  // namespace sandphys::bench
