// The CPU twin of shaders/sim/state_hash.comp, and the comparison of two snapshots that names
// the first difference.
#include <algorithm>
#include <bit>
#include <cinttypes>
#include <cstdio>
#include <cstring>

#include "sandphys/recording.h"

namespace sandphys {

namespace {

std::uint32_t fmix(std::uint32_t h) {
  h ^= h >> 16;
  h *= 0x85ebca6bu;
  h ^= h >> 13;
  h *= 0xc2b2ae35u;
  h ^= h >> 16;
  return h;
}

struct Lanes {
  std::uint32_t x;
  std::uint32_t y;
};

Lanes absorb(Lanes h, std::uint32_t word) {
  return {fmix(h.x ^ word) + 0x9e3779b9u, fmix(h.y ^ (word * 0x27d4eb2fu)) + 0x7f4a7c15u};
}

Lanes absorb(Lanes h, float value) {
  return absorb(h, std::bit_cast<std::uint32_t>(value));
}

// The float fields of a stored body and of a pushed body state, in the order they are compared
// and named; names are built only for a difference.
struct StoredField {
  const char* name;
  float (*of)(const StoredBody&);
};
constexpr StoredField kStoredFields[] = {
    {"position.x", [](const StoredBody& b) { return b.position[0]; }},
    {"position.y", [](const StoredBody& b) { return b.position[1]; }},
    {"position.z", [](const StoredBody& b) { return b.position[2]; }},
    {"principalOrientation.w", [](const StoredBody& b) { return b.principalOrientation.w; }},
    {"principalOrientation.x", [](const StoredBody& b) { return b.principalOrientation.x; }},
    {"principalOrientation.y", [](const StoredBody& b) { return b.principalOrientation.y; }},
    {"principalOrientation.z", [](const StoredBody& b) { return b.principalOrientation.z; }},
    {"velocity.x", [](const StoredBody& b) { return b.velocity[0]; }},
    {"velocity.y", [](const StoredBody& b) { return b.velocity[1]; }},
    {"velocity.z", [](const StoredBody& b) { return b.velocity[2]; }},
    {"angularVelocity.x", [](const StoredBody& b) { return b.angularVelocity[0]; }},
    {"angularVelocity.y", [](const StoredBody& b) { return b.angularVelocity[1]; }},
    {"angularVelocity.z", [](const StoredBody& b) { return b.angularVelocity[2]; }},
};

struct DescField {
  const char* name;
  float (*of)(const BodyDesc&);
};
constexpr DescField kDescFields[] = {
    {"position.x", [](const BodyDesc& d) { return d.position.x; }},
    {"position.y", [](const BodyDesc& d) { return d.position.y; }},
    {"position.z", [](const BodyDesc& d) { return d.position.z; }},
    {"orientation.w", [](const BodyDesc& d) { return d.orientation.w; }},
    {"orientation.x", [](const BodyDesc& d) { return d.orientation.x; }},
    {"orientation.y", [](const BodyDesc& d) { return d.orientation.y; }},
    {"orientation.z", [](const BodyDesc& d) { return d.orientation.z; }},
    {"velocity.x", [](const BodyDesc& d) { return d.velocity.x; }},
    {"velocity.y", [](const BodyDesc& d) { return d.velocity.y; }},
    {"velocity.z", [](const BodyDesc& d) { return d.velocity.z; }},
    {"angularVelocity.x", [](const BodyDesc& d) { return d.angularVelocity.x; }},
    {"angularVelocity.y", [](const BodyDesc& d) { return d.angularVelocity.y; }},
    {"angularVelocity.z", [](const BodyDesc& d) { return d.angularVelocity.z; }},
};

bool sameBits(float a, float b) {
  return std::bit_cast<std::uint32_t>(a) == std::bit_cast<std::uint32_t>(b);
}

std::string floatText(double value) {
  const float f = static_cast<float>(value);
  char text[64];
  std::snprintf(text, sizeof text, "%.9g (0x%08" PRIx32 ")", value,
                std::bit_cast<std::uint32_t>(f));
  return text;
}

}  // namespace

std::uint64_t stateHash(const WorldSnapshot& snapshot) {
  std::uint32_t low = 0;
  std::uint32_t high = 0;
  for (std::uint32_t i = 0; i < snapshot.bodies.size(); ++i) {
    const StoredBody& b = snapshot.bodies[i];
    Lanes h{fmix(i ^ 0x243f6a88u), fmix(i ^ 0x85a308d3u)};
    for (float v : b.position) h = absorb(h, v);
    for (float v : orientationWords(b)) h = absorb(h, v);
    for (float v : b.velocity) h = absorb(h, v);
    for (float v : b.angularVelocity) h = absorb(h, v);
    h = absorb(h, statusWord(b));
    if (!snapshot.bodyIds.empty() && snapshot.bodyIds[i] != i) h = absorb(h, snapshot.bodyIds[i]);
    low += h.x;
    high += h.y;
  }
  // The slots in the order the GPU reads them: the first slot of each of the three group
  // buffers, then the second of each, and so on.
  constexpr std::uint32_t kGroups = 3;
  constexpr std::uint32_t kPerGroup = kContactSlots / kGroups;
  for (std::uint32_t i = 0; i < snapshot.contacts.size(); ++i) {
    const StoredContacts& c = snapshot.contacts[i];
    Lanes h{fmix(i ^ 0x13198a2eu), fmix(i ^ 0x03707344u)};
    for (std::uint32_t g = 0; g < kPerGroup; ++g) {
      for (std::uint32_t group = 0; group < kGroups; ++group) {
        for (std::uint32_t word : c.slots[group * kPerGroup + g]) h = absorb(h, word);
      }
    }
    for (std::uint32_t word : c.pairs) h = absorb(h, word);
    low += h.x;
    high += h.y;
  }
  for (std::uint32_t i = 0; i < snapshot.rolling.size(); ++i) {
    Lanes h{fmix(i ^ 0xbe5466cfu), fmix(i ^ 0x34e90c6cu)};
    for (const auto& spring : snapshot.rolling[i].springs) {
      for (std::uint32_t word : spring) h = absorb(h, word);
    }
    low += h.x;
    high += h.y;
  }
  for (std::uint32_t i = 0; i < snapshot.forces.size(); ++i) {
    const StoredForces& f = snapshot.forces[i];
    Lanes h{fmix(i ^ 0xa4093822u), fmix(i ^ 0x299f31d0u)};
    for (std::uint32_t word : f.force) h = absorb(h, word);
    for (std::uint32_t word : f.torque) h = absorb(h, word);
    low += h.x;
    high += h.y;
  }
  return (std::uint64_t(high) << 32) | low;
}

std::string StateDifference::describe() const {
  std::string text = std::string(subject == Subject::Particle ? "particle " : "body ") +
                     std::to_string(body) + " " + field + ": recorded ";
  if (integer || field == "body count" || field == "alive" || field == "calm" || field == "body" ||
      field == "body id" || field == "motion") {
    return text + std::to_string(static_cast<long long>(recorded)) + ", replayed " +
           std::to_string(static_cast<long long>(replayed));
  }
  return text + floatText(recorded) + ", replayed " + floatText(replayed);
}

std::optional<StateDifference> firstDifference(const WorldSnapshot& recorded,
                                               const WorldSnapshot& replayed) {
  const std::size_t common = std::min(recorded.bodies.size(), replayed.bodies.size());
  for (std::size_t i = 0; i < common; ++i) {
    const StoredBody& a = recorded.bodies[i];
    const StoredBody& b = replayed.bodies[i];
    for (const StoredField& field : kStoredFields) {
      if (!sameBits(field.of(a), field.of(b))) {
        return StateDifference{std::uint32_t(i), field.name, field.of(a), field.of(b)};
      }
    }
    if (a.alive != b.alive) {
      return StateDifference{std::uint32_t(i), "alive", double(a.alive), double(b.alive)};
    }
    if (a.calm != b.calm) {
      return StateDifference{std::uint32_t(i), "calm", double(a.calm), double(b.calm)};
    }
    const auto id = [&](const WorldSnapshot& s) {
      return s.bodyIds.empty() ? double(i) : double(s.bodyIds[i]);
    };
    if (id(recorded) != id(replayed)) {
      return StateDifference{std::uint32_t(i), "body id", id(recorded), id(replayed)};
    }
  }
  if (recorded.bodies.size() != replayed.bodies.size()) {
    return StateDifference{std::uint32_t(common), "body count", double(recorded.bodies.size()),
                           double(replayed.bodies.size())};
  }
  // Contact history: named by particle, slot and word.
  const std::size_t particles = std::min(recorded.contacts.size(), replayed.contacts.size());
  for (std::size_t i = 0; i < particles; ++i) {
    const StoredContacts& a = recorded.contacts[i];
    const StoredContacts& b = replayed.contacts[i];
    for (std::uint32_t k = 0; k < kContactSlots; ++k) {
      for (std::uint32_t w = 0; w < 4; ++w) {
        if (a.slots[k][w] == b.slots[k][w]) continue;
        static constexpr const char* kWords[4] = {"spring.x", "spring.y", "spring.z", "key"};
        const bool isFloat = w < 3;
        return StateDifference{
            std::uint32_t(i),
            "contact slot " + std::to_string(k) + " " + kWords[w],
            isFloat ? double(std::bit_cast<float>(a.slots[k][w])) : double(a.slots[k][w]),
            isFloat ? double(std::bit_cast<float>(b.slots[k][w])) : double(b.slots[k][w]),
            StateDifference::Subject::Particle,
            !isFloat};
      }
    }
    for (std::uint32_t w = 0; w < a.pairs.size(); ++w) {
      if (a.pairs[w] != b.pairs[w]) {
        return StateDifference{
            std::uint32_t(i),   "contact pairs " + std::to_string(w), double(a.pairs[w]),
            double(b.pairs[w]), StateDifference::Subject::Particle,   true};
      }
    }
  }
  if (recorded.contacts.size() != replayed.contacts.size()) {
    return StateDifference{std::uint32_t(particles),           "particle count",
                           double(recorded.contacts.size()),   double(replayed.contacts.size()),
                           StateDifference::Subject::Particle, true};
  }
  // Rolling springs (rolling friction): named by particle, slot and word.
  const std::size_t rolled = std::min(recorded.rolling.size(), replayed.rolling.size());
  for (std::size_t i = 0; i < rolled; ++i) {
    for (std::uint32_t k = 0; k < kContactSlots; ++k) {
      for (std::uint32_t w = 0; w < 3; ++w) {
        const std::uint32_t a = recorded.rolling[i].springs[k][w];
        const std::uint32_t b = replayed.rolling[i].springs[k][w];
        if (a == b) continue;
        return StateDifference{std::uint32_t(i),
                               "contact slot " + std::to_string(k) + " rolling." + "xyz"[w],
                               double(std::bit_cast<float>(a)),
                               double(std::bit_cast<float>(b)),
                               StateDifference::Subject::Particle,
                               false};
      }
    }
  }
  if (recorded.rolling.size() != replayed.rolling.size()) {
    return StateDifference{std::uint32_t(rolled),
                           "rolling count",
                           double(recorded.rolling.size()),
                           double(replayed.rolling.size()),
                           StateDifference::Subject::Particle,
                           true};
  }
  // Forces (sleep): named by particle and word; the force's w is an integer (a calm count).
  const std::size_t loaded = std::min(recorded.forces.size(), replayed.forces.size());
  for (std::size_t i = 0; i < loaded; ++i) {
    for (const bool torque : {false, true}) {
      const auto& a = torque ? recorded.forces[i].torque : recorded.forces[i].force;
      const auto& b = torque ? replayed.forces[i].torque : replayed.forces[i].force;
      for (std::uint32_t w = 0; w < 4; ++w) {
        if (a[w] == b[w]) continue;
        const bool isFloat = w < 3 || torque;
        return StateDifference{std::uint32_t(i),
                               std::string(torque ? "torque." : "force.") + "xyzw"[w],
                               isFloat ? double(std::bit_cast<float>(a[w])) : double(a[w]),
                               isFloat ? double(std::bit_cast<float>(b[w])) : double(b[w]),
                               StateDifference::Subject::Particle,
                               !isFloat};
      }
    }
  }
  if (recorded.forces.size() != replayed.forces.size()) {
    return StateDifference{std::uint32_t(loaded),
                           "forces count",
                           double(recorded.forces.size()),
                           double(replayed.forces.size()),
                           StateDifference::Subject::Particle,
                           true};
  }
  return std::nullopt;
}

std::optional<StateDifference> firstDifference(const RecordedInput& recorded,
                                               const RecordedInput& replayed) {
  if (recorded.body != replayed.body) {
    return StateDifference{recorded.body, "body", double(recorded.body), double(replayed.body)};
  }
  for (const DescField& field : kDescFields) {
    if (!sameBits(field.of(recorded.state), field.of(replayed.state))) {
      return StateDifference{recorded.body, field.name, field.of(recorded.state),
                             field.of(replayed.state)};
    }
  }
  if (recorded.state.motion != replayed.state.motion) {
    return StateDifference{recorded.body, "motion", double(recorded.state.motion),
                           double(replayed.state.motion)};
  }
  return std::nullopt;
}

}  // namespace sandphys
