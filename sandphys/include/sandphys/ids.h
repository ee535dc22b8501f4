#pragma once

#include <cstdint>

namespace sandphys {

/// A rigid body (granule, sampled mesh, rough floor) in a World: slot index plus generation.
/// A default id is invalid; an id whose body was removed is stale and rejected with InvalidId.
struct BodyId {
  static constexpr std::uint32_t kInvalidIndex = 0xffffffffu;
  std::uint32_t index = kInvalidIndex;
  std::uint32_t generation = 0;
  bool isValid() const { return index != kInvalidIndex; }
  friend bool operator==(BodyId, BodyId) = default;
};

/// An implicit collider (plane, box, cylinder wall, funnel) in a World.
struct ColliderId {
  std::uint32_t index = 0xffffffffu;
  bool isValid() const { return index != 0xffffffffu; }
  friend bool operator==(ColliderId, ColliderId) = default;
};

/// A granule emitter in a World.
struct EmitterId {
  std::uint32_t index = 0xffffffffu;
  bool isValid() const { return index != 0xffffffffu; }
  friend bool operator==(EmitterId, EmitterId) = default;
};

/// A kill volume (sink) in a World.
struct SinkId {
  std::uint32_t index = 0xffffffffu;
  bool isValid() const { return index != 0xffffffffu; }
  friend bool operator==(SinkId, SinkId) = default;
};

}  // namespace sandphys
