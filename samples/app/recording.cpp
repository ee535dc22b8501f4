// --record: a run of a scene written as it goes (docs/recording.md), and the text of its settings.
#include "app/recording.h"

#include <charconv>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <system_error>

#include "scenes/scene_parameters.h"

namespace sandphys::samples {

namespace {

using Clock = std::chrono::steady_clock;

constexpr std::size_t kToolEventBytes = 1 + 6 * sizeof(float);

std::string exactText(double value) {
  char text[64];
  const auto result = std::to_chars(text, text + sizeof text, value);
  return std::string(text, result.ptr);
}

// Every field of WorldSettings as a recording names it ("world:KEY"), from the library's table:
// reals exactly (shortest text that reads back to the same float), flags 0/1, the law by name.
void appendWorldSettingsImpl(WorldSettings settings,
                             std::vector<std::pair<std::string, std::string>>& out) {
  for (const SettingField& field : worldSettingFields()) {
    std::string text;
    switch (field.kind) {
      case SettingField::Kind::Real:
        text = exactText(*field.real(settings));
        break;
      case SettingField::Kind::Count:
        text = std::to_string(*field.count(settings));
        break;
      case SettingField::Kind::Flag:
        text.push_back(*field.flag(settings) ? '1' : '0');
        break;
      case SettingField::Kind::Law:
        text = std::string(scenes::contactLawName(*field.law(settings)));
        break;
    }
    out.emplace_back(std::string(kWorldPrefix) + field.key, std::move(text));
  }
}

}  // namespace

WorldSettings worldSettingsFrom(const Recording& recording, WorldSettings settings) {
  const std::size_t prefix = std::strlen(kWorldPrefix);
  for (const auto& [key, text] : recording.settings) {
    if (key.compare(0, prefix, kWorldPrefix) != 0) continue;
    const std::string name = key.substr(prefix);
    auto refuse = [&] {
      return RecordingError("recording '" + recording.file.string() +
                            "': this build refuses its setting " + key + " = " + text);
    };
    auto parse = [&](auto& value) {
      const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
      if (result.ec != std::errc() || result.ptr != text.data() + text.size()) throw refuse();
    };
    const SettingField* field = findWorldSettingField(name);
    if (!field) throw refuse();
    switch (field->kind) {
      case SettingField::Kind::Real:
        parse(*field->real(settings));
        break;
      case SettingField::Kind::Count:
        parse(*field->count(settings));
        break;
      case SettingField::Kind::Flag:
        if (text != "0" && text != "1") throw refuse();
        *field->flag(settings) = text == "1";
        break;
      case SettingField::Kind::Law: {
        const std::optional<ContactLaw> law = scenes::contactLawFromName(text);
        if (!law) throw refuse();
        *field->law(settings) = *law;
        break;
      }
    }
  }
  return settings;
}

SceneRecorder::SceneRecorder(const std::filesystem::path& file, scenes::Scene& scene,
                             const WorldSettings& world, double frameDt,
                             std::uint64_t snapshotEvery, const std::string& device, bool sandTools)
    : m_writer(file,
               [&] {
                 std::vector<std::pair<std::string, std::string>> settings{
                     {"scene", std::string(scene.name())},
                     {"frame_dt", exactText(frameDt)},
                     {"snapshot_every", std::to_string(snapshotEvery)},
                     {"device", device}};
                 for (const scenes::SceneParameter& parameter : scene.parameters()) {
                   settings.emplace_back(kParameterPrefix + parameter.name,
                                         scenes::formatSceneParameter(parameter));
                 }
                 appendWorldSettingsImpl(world, settings);
                 if (sandTools) settings.emplace_back(kToolsKey, kSandTools);
                 return settings;
               }()),
      m_snapshotEvery(std::max<std::uint64_t>(snapshotEvery, 1)) {}

void SceneRecorder::begin(World& world) {
  m_writer.addSnapshot(world.readSnapshot());
  m_start = Clock::now();
}

void SceneRecorder::recordFrame(World& world, const scenes::Scene& scene, float frameDt,
                                std::uint64_t frame, const std::vector<std::uint8_t>& events) {
  const Clock::time_point start = Clock::now();
  RecordedFrame record;
  record.frameDt = frameDt;
  record.steps = world.stepCount();
  record.simulatedTime = world.simulatedTime();
  record.stateHash = world.readStateHash();
  record.inputs = scene.externalInputs();
  record.events = events;
  m_writer.addFrame(record);
  m_frames = frame;
  if (frame % m_snapshotEvery == 0) {
    WorldSnapshot snapshot = world.readSnapshot();
    snapshot.frame = frame;
    m_writer.addSnapshot(snapshot);
    m_lastSnapshot = frame;
  }
  m_ownSeconds += std::chrono::duration<double>(Clock::now() - start).count();
}

std::uint64_t SceneRecorder::finish(World& world) {
  const double wallSeconds =
      std::chrono::duration<double>(Clock::now() - m_start).count() - m_ownSeconds;
  if (m_frames > 0 && m_lastSnapshot != m_frames) {
    WorldSnapshot snapshot = world.readSnapshot();
    snapshot.frame = m_frames;
    m_writer.addSnapshot(snapshot);
  }
  return m_writer.finish(wallSeconds);
}

std::vector<std::uint8_t> toolEvents(bool pour, bool push, const samples::Ray& cursor) {
  if (!pour && !push) return {};
  std::vector<std::uint8_t> events(kToolEventBytes);
  events[0] = std::uint8_t((pour ? 1u : 0u) | (push ? 2u : 0u));
  const float values[6] = {cursor.origin.x(),    cursor.origin.y(),    cursor.origin.z(),
                           cursor.direction.x(), cursor.direction.y(), cursor.direction.z()};
  std::memcpy(events.data() + 1, values, sizeof values);
  return events;
}

ToolInput readToolEvents(const Recording& recording, std::uint64_t frame) {
  const std::vector<std::uint8_t>& events = recording.frames.at(frame - 1).events;
  ToolInput input;
  if (events.empty()) return input;
  if (events.size() != kToolEventBytes || events[0] == 0 || events[0] > 3) {
    throw RecordingError("recording '" + recording.file.string() + "': frame " +
                         std::to_string(frame) + " has " + std::to_string(events.size()) +
                         " bytes of events that are not the sand tools' input");
  }
  input.pour = (events[0] & 1u) != 0;
  input.push = (events[0] & 2u) != 0;
  float values[6];
  std::memcpy(values, events.data() + 1, sizeof values);
  input.cursor.origin = {values[0], values[1], values[2]};
  input.cursor.direction = {values[3], values[4], values[5]};
  return input;
}

}  // namespace sandphys::samples
