#pragma once

#include <cstddef>
#include <cstdint>

namespace sandphys {

/// A rigid body (granule, sampled mesh, rough floor) in a World: its index, the slot it was added
/// in (a sort of the granules by place, WorldSettings::sortInterval, moves its state to another
/// slot, never its id), plus generation.
/// A default id is invalid; an id whose body was removed is stale and rejected with InvalidId.
struct BodyId {
  static constexpr std::uint32_t kInvalidIndex = 0xffffffffu;
  std::uint32_t index = kInvalidIndex;
  std::uint32_t generation = 0;
  bool isValid() const { return index != kInvalidIndex; }
  friend bool operator==(BodyId, BodyId) = default;
};

/// The bodies one call added together (World::addGranules with a GranuleBlock), as typed ids:
/// `for (BodyId id : range)`, `range[i]`, `range.contains(id)`. Only a World makes one; a default
/// range is empty.
class BodyRange {
 public:
  /// Walks the range's ids in the order the bodies were added.
  class Iterator {
   public:
    using value_type = BodyId;
    using difference_type = std::ptrdiff_t;
    Iterator() = default;
    BodyId operator*() const { return m_id; }
    Iterator& operator++() {
      ++m_id.index;
      return *this;
    }
    Iterator operator++(int) {
      Iterator before = *this;
      ++m_id.index;
      return before;
    }
    friend bool operator==(Iterator, Iterator) = default;

   private:
    friend class BodyRange;
    explicit Iterator(BodyId id) : m_id(id) {}
    BodyId m_id;
  };

  BodyRange() = default;
  std::uint32_t size() const { return m_count; }
  bool empty() const { return m_count == 0; }
  /// The i-th body added; throws InvalidArgument naming i and the size unless i < size().
  BodyId operator[](std::uint32_t i) const;
  Iterator begin() const { return Iterator(m_first); }
  Iterator end() const { return Iterator(BodyId{m_first.index + m_count, m_first.generation}); }
  /// `id` is one of the range's bodies (the same slot and generation).
  bool contains(BodyId id) const {
    return id.generation == m_first.generation && id.index - m_first.index < m_count;
  }

 private:
  friend class World;
  // Consecutive slots, all of the first one's generation (World::addGranules checks it).
  BodyRange(BodyId first, std::uint32_t count) : m_first(first), m_count(count) {}
  BodyId m_first;
  std::uint32_t m_count = 0;
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
