// World's bodies: granule blocks, rough floors and bodies built from templates, checked, counted
// before they are built (the slots they go to: world_body_slots.cpp); emitters; poses set from
// the CPU.
#include "sandphys/world.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/assert.h"
#include "core/granule_spawner.h"
#include "core/overlap_check.h"
#include "core/validation.h"
#include "core/world_checks.h"
#include "core/world_impl.h"

namespace sandphys {

using namespace detail;

BodyId World::addRoughFloor(const RoughFloor& floor) {
  requireFiniteVec("RoughFloor.center", floor.center);
  requireNonNegative("RoughFloor.radius", floor.radius, "(m)");
  requireNonNegative("RoughFloor.spacing", floor.spacing, "(m)");
  const float d = impl().settings.particleDiameter;
  const double spacing = floor.spacing > 0.0f ? floor.spacing : d;
  double hx = floor.radius, hz = floor.radius;
  if (floor.radius == 0.0f) {
    requirePositive("RoughFloor.halfExtentX", floor.halfExtentX, "(m) (or give a radius)");
    requirePositive("RoughFloor.halfExtentZ", floor.halfExtentZ, "(m) (or give a radius)");
    hx = floor.halfExtentX;
    hz = floor.halfExtentZ;
  }
  if (impl().keepsHistory()) {
    // A granule landing on the floor at maxSpeed must not slip between its particles.
    requireNoPassThrough(
        impl().settings, impl().model.peakOverlapFixedParticle, floorPassOverlap(spacing / d),
        "a granule meeting a RoughFloor of spacing " + formatValue(spacing / d) + " d at maxSpeed");
  }
  requireResolvable("RoughFloor.center", floor.center, std::sqrt(hx * hx + hz * hz), d);
  // Counted before anything is built: a floor too large for the World costs no memory.
  Impl& w = impl();
  const std::uint64_t room = std::uint64_t(w.particleCapacity) - w.particleCount;
  const double radius = floor.radius;
  w.requireRoom(1, roughFloorParticles(spacing, hx, hz, radius, room));
  const auto nx = std::int64_t(roughFloorSteps(hx, spacing));
  const auto nz = std::int64_t(roughFloorSteps(hz, spacing));
  std::vector<Vec3> centres;
  for (std::int64_t z = -nz; z <= nz; ++z) {
    for (std::int64_t x = -nx; x <= nx; ++x) {
      double px = double(x) * spacing, pz = double(z) * spacing;
      if (radius > 0.0 && !inRoughFloor(px, pz, radius, spacing)) continue;
      centres.push_back({float(px), 0.0f, float(pz)});
    }
  }
  // A static body: its mass does not matter; keep the template frame (no principal rotation).
  ParticleTemplate shape;
  shape.offsets = centres;
  shape.mass = 1.0f;
  shape.principalInertia = {1.0f, 1.0f, 1.0f};
  shape.boundingRadius = float(std::sqrt(hx * hx + hz * hz));
  const std::uint32_t slot =
      w.addBodies(shape, {BodyDesc{floor.center, {}, {}, {}, Motion::Static}}, false);
  w.checkOverlapsFrom(slot);
  return w.bodyId(slot);
}

BodyId World::addBody(const ParticleTemplate& shape, const BodyDesc& desc) {
  requireTemplate(shape);
  impl().requireImpenetrableSurface(shape);
  requireFiniteVec("BodyDesc.position", desc.position);
  requireResolvable("BodyDesc.position", desc.position, shape.boundingRadius,
                    impl().settings.particleDiameter);
  requireFiniteVec("BodyDesc.velocity", desc.velocity);
  requireFiniteVec("BodyDesc.angularVelocity", desc.angularVelocity);
  BodyDesc d = desc;
  d.orientation = normalised(desc.orientation, "BodyDesc.orientation");
  const std::uint32_t slot = impl().addBodies(shape, {d}, false);
  impl().checkOverlapsFrom(slot);
  return impl().bodyId(slot);
}

BodyRange World::addGranules(const GranuleBlock& block) {
  Impl& w = impl();
  const float d = w.settings.particleDiameter;
  const double spacing = granuleBlockSpacing(block, d);
  // Counted and placed before anything is built: a block too large for the World costs no
  // memory.
  const auto count =
      std::uint64_t(std::min(double(block.countX) * block.countY * block.countZ, 0x1.0p60));
  w.requireRoom(count, count * w.granule.offsets.size());
  const auto halfExtent = [&](std::uint32_t n) {
    return (0.5 * (n - 1.0) + double(block.jitter)) * spacing;
  };
  requireResolvable(
      "GranuleBlock.center", block.center,
      std::hypot(halfExtent(block.countX), halfExtent(block.countY), halfExtent(block.countZ)) +
          w.granule.boundingRadius,
      d);
  auto spawns = layoutGranuleBlock(block, d);
  std::vector<BodyDesc> descs;
  descs.reserve(spawns.size());
  for (const auto& s : spawns)
    descs.push_back({s.position, s.orientation, s.velocity, {}, Motion::Dynamic});
  const std::uint32_t first = w.addBodies(w.granule, descs, true);
  w.checkOverlapsFrom(first);
  const BodyRange range(w.bodyId(first), std::uint32_t(descs.size()));
  for (std::uint32_t i = 0; i < range.size(); ++i) {
    SANDPHYS_ASSERT(w.bodyId(first + i) == range[i],
                    "new body slot " + std::to_string(first + i) +
                        " has another generation than the first of its range");
  }
  return range;
}

std::vector<BodyId> World::addGranules(std::span<const BodyDesc> granules) {
  Impl& w = impl();
  std::vector<BodyDesc> descs(granules.begin(), granules.end());
  for (std::size_t i = 0; i < descs.size(); ++i) {
    const std::string field = "granules[" + std::to_string(i) + "]";
    BodyDesc& d = descs[i];
    require(d.motion == Motion::Dynamic, field + ".motion", double(unsigned(d.motion)),
            "must be Motion::Dynamic (a kinematic or static body: addBody)");
    requireFiniteVec(field + ".position", d.position);
    requireResolvable(field + ".position", d.position, w.granule.boundingRadius,
                      w.settings.particleDiameter);
    requireFiniteVec(field + ".velocity", d.velocity);
    requireFiniteVec(field + ".angularVelocity", d.angularVelocity);
    d.orientation = normalised(d.orientation, field + ".orientation");
  }
  std::vector<BodyId> ids;
  if (descs.empty()) return ids;
  const std::uint32_t first = w.addBodies(w.granule, descs, true);
  w.checkOverlapsFrom(first);
  ids.reserve(descs.size());
  for (std::uint32_t i = first; i < first + descs.size(); ++i) ids.push_back(w.bodyId(i));
  return ids;
}

BodyId BodyRange::operator[](std::uint32_t i) const {
  if (i >= m_count) {
    throw InvalidArgument("BodyRange index " + std::to_string(i) + " is out of range (size " +
                          std::to_string(m_count) + ")");
  }
  return BodyId{m_first.index + i, m_first.generation};
}

EmitterId World::addEmitter(const EmitterSettings& emitter) {
  Impl& w = impl();
  w.emitters.emplace_back(EmitterState(emitter, w.settings.particleDiameter, w.bodyCapacity));
  return EmitterId{std::uint32_t(impl().emitters.size() - 1)};
}

void World::removeEmitter(EmitterId id) {
  if (!id.isValid() || id.index >= impl().emitters.size() || !impl().emitters[id.index]) {
    throw InvalidId("EmitterId " + std::to_string(id.index) + " does not exist");
  }
  impl().emitters[id.index].reset();
}

void World::setBodyState(BodyId id, const BodyDesc& state) {
  impl().requireBody(id);
  requireFiniteVec("BodyDesc.position", state.position);
  requireFiniteVec("BodyDesc.velocity", state.velocity);
  requireFiniteVec("BodyDesc.angularVelocity", state.angularVelocity);
  Impl& w = impl();
  const std::uint32_t slot = w.slotOf(id.index);
  requireResolvable("BodyDesc.position", state.position, w.boundingRadii[slot],
                    w.settings.particleDiameter);
  BodyDesc d = state;
  d.orientation = normalised(state.orientation, "BodyDesc.orientation");
  const Motion added = w.bodyMotions[slot];
  if (state.motion != added) {
    throw InvalidArgument("BodyDesc.motion = " + std::to_string(unsigned(state.motion)) +
                          " for body " + std::to_string(id.index) +
                          ": a body keeps the motion it was added with (" +
                          std::to_string(unsigned(added)) + "; 0 dynamic, 1 kinematic, 2 static)");
  }
  w.gpu->makeCurrent();
  w.placeBody(slot, d);
}

}  // namespace sandphys
