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

template <std::size_t N>
void appendFields(std::vector<std::pair<std::string, float>>& out, const char* name,
                  const std::array<float, N>& values) {
  static constexpr const char* kAxes[] = {"x", "y", "z", "w"};
  for (std::size_t i = 0; i < N; ++i)
    out.emplace_back(std::string(name) + "." + kAxes[i], values[i]);
}

std::vector<std::pair<std::string, float>> fieldsOf(const StoredBody& body) {
  std::vector<std::pair<std::string, float>> fields;
  fields.reserve(13);
  appendFields(fields, "position", body.position);
  appendFields(fields, "orientation", body.orientation);
  appendFields(fields, "velocity", body.velocity);
  appendFields(fields, "angularVelocity", body.angularVelocity);
  return fields;
}

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
    for (float v : b.orientation) h = absorb(h, v);
    for (float v : b.velocity) h = absorb(h, v);
    for (float v : b.angularVelocity) h = absorb(h, v);
    h = absorb(h, std::uint32_t(b.alive ? 1u : 0u));
    low += h.x;
    high += h.y;
  }
  return (std::uint64_t(high) << 32) | low;
}

std::string StateDifference::describe() const {
  std::string text = "body " + std::to_string(body) + " " + field + ": recorded ";
  if (field == "body count" || field == "alive") {
    return text + std::to_string(static_cast<long long>(recorded)) + ", replayed " +
           std::to_string(static_cast<long long>(replayed));
  }
  return text + floatText(recorded) + ", replayed " + floatText(replayed);
}

std::optional<StateDifference> firstDifference(const WorldSnapshot& recorded,
                                               const WorldSnapshot& replayed) {
  const std::size_t common = std::min(recorded.bodies.size(), replayed.bodies.size());
  for (std::size_t i = 0; i < common; ++i) {
    const auto a = fieldsOf(recorded.bodies[i]);
    const auto b = fieldsOf(replayed.bodies[i]);
    for (std::size_t f = 0; f < a.size(); ++f) {
      if (!sameBits(a[f].second, b[f].second)) {
        return StateDifference{std::uint32_t(i), a[f].first, a[f].second, b[f].second};
      }
    }
    if (recorded.bodies[i].alive != replayed.bodies[i].alive) {
      return StateDifference{std::uint32_t(i), "alive", double(recorded.bodies[i].alive),
                             double(replayed.bodies[i].alive)};
    }
  }
  if (recorded.bodies.size() != replayed.bodies.size()) {
    return StateDifference{std::uint32_t(common), "body count", double(recorded.bodies.size()),
                           double(replayed.bodies.size())};
  }
  return std::nullopt;
}

}  // namespace sandphys
