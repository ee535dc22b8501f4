#include "core/world_checks.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "core/validation.h"
#include "sandphys/colliders.h"
#include "sandphys/settings.h"

namespace sandphys::detail {
namespace {

// How far a unit quaternion's squared norm may stray: float rounding of a normalised one stays
// far inside it.
constexpr double kUnitTolerance = 1e-4;

void requireUnit(const std::string& field, Quat q) {
  double n2 = 0.0;
  for (const float v : {q.w, q.x, q.y, q.z}) n2 += double(v) * v;
  require(std::isfinite(n2) && std::abs(n2 - 1.0) <= kUnitTolerance, field + " (squared norm)", n2,
          "must be a unit quaternion (finite, squared norm 1 within " +
              formatValue(kUnitTolerance) + ")");
}

}  // namespace

void requireFiniteVec(const std::string& field, Vec3 v) {
  requireFinite(field + ".x", v.x);
  requireFinite(field + ".y", v.y);
  requireFinite(field + ".z", v.z);
}

Quat normalised(Quat q, const std::string& field) {
  double n =
      std::sqrt(double(q.w) * q.w + double(q.x) * q.x + double(q.y) * q.y + double(q.z) * q.z);
  require(std::isfinite(n) && n > 1e-6, field, n, "must be a non-zero, finite quaternion");
  return {float(q.w / n), float(q.x / n), float(q.y / n), float(q.z / n)};
}

void requireResolvable(const std::string& field, Vec3 position, double reach,
                       float particleDiameter) {
  const double largest = std::max({std::abs(double(position.x)), std::abs(double(position.y)),
                                   std::abs(double(position.z))}) +
                         std::max(reach, 0.0);
  // A float's spacing at x is at most x · 2^-23; positions up to this many d apart are resolved.
  const double limit = double(kMaxPositionSpacing) * particleDiameter * 0x1.0p23;
  require(largest <= limit, field + " (farthest coordinate, m)", largest,
          "must be <= " + formatValue(limit) + " m (" + formatValue(limit / particleDiameter) +
              " particle diameters) from the origin: beyond it a float cannot tell positions " +
              formatValue(kMaxPositionSpacing) +
              " d apart, and contacts are resolved in smaller overlaps; move the scene nearer "
              "the origin");
}

void requireTemplate(const ParticleTemplate& shape) {
  require(!shape.offsets.empty(), "ParticleTemplate.offsets (count)", 0, "must not be empty");
  requirePositive("ParticleTemplate.mass", shape.mass, "(kg)");
  requirePositive("ParticleTemplate.principalInertia.x", shape.principalInertia.x, "(kg m^2)");
  requirePositive("ParticleTemplate.principalInertia.y", shape.principalInertia.y, "(kg m^2)");
  requirePositive("ParticleTemplate.principalInertia.z", shape.principalInertia.z, "(kg m^2)");
  requireUnit("ParticleTemplate.principalRotation", shape.principalRotation);
  requireNonNegative("ParticleTemplate.boundingRadius", shape.boundingRadius, "(m)");
  requireNonNegative("ParticleTemplate.surfaceSpacing", shape.surfaceSpacing, "(m)");
  double farthest = 0.0;
  for (std::size_t i = 0; i < shape.offsets.size(); ++i) {
    const Vec3& o = shape.offsets[i];
    requireFiniteVec("ParticleTemplate.offsets[" + std::to_string(i) + "]", o);
    farthest =
        std::max(farthest, std::sqrt(double(o.x) * o.x + double(o.y) * o.y + double(o.z) * o.z));
  }
  // The radius bounds where the body may touch (sleep, colliders' wake boxes): it must hold them.
  require(farthest <= double(shape.boundingRadius) * (1.0 + 1e-5) + 1e-9,
          "ParticleTemplate.boundingRadius", shape.boundingRadius,
          "must be >= the farthest offset, " + formatValue(farthest) + " m");
}

void requireRestorable(const WorldSnapshot& snapshot) {
  requireNonNegative("WorldSnapshot.simulatedTime", snapshot.simulatedTime, "(s)");
  requireNonNegative("WorldSnapshot.unsteppedTime", snapshot.unsteppedTime, "(s)");
  for (std::size_t i = 0; i < snapshot.bodies.size(); ++i) {
    const StoredBody& b = snapshot.bodies[i];
    const std::string slot = "WorldSnapshot.bodies[" + std::to_string(i) + "]";
    for (int k = 0; k < 3; ++k) {
      const std::string axis(1, "xyz"[k]);
      requireFinite(slot + ".position." + axis, b.position[k]);
      requireFinite(slot + ".velocity." + axis, b.velocity[k]);
      requireFinite(slot + ".angularVelocity." + axis, b.angularVelocity[k]);
    }
    requireUnit(slot + ".principalOrientation", b.principalOrientation);
    require(b.calm < (1u << 30), slot + ".calm", b.calm, "must be < 2^30");
  }
  if (!snapshot.bodyIds.empty()) {
    require(snapshot.bodyIds.size() == snapshot.bodies.size(), "WorldSnapshot.bodyIds.size()",
            double(snapshot.bodyIds.size()),
            "must be 0 or the number of bodies, " + std::to_string(snapshot.bodies.size()));
    std::vector<bool> seen(snapshot.bodyIds.size());
    for (std::size_t i = 0; i < snapshot.bodyIds.size(); ++i) {
      const std::uint32_t id = snapshot.bodyIds[i];
      require(id < seen.size() && !seen[id], "WorldSnapshot.bodyIds[" + std::to_string(i) + "]", id,
              "must be below the number of bodies and name no body twice");
      seen[id] = true;
    }
  }
  for (std::size_t p = 0; p < snapshot.contacts.size(); ++p) {
    const StoredContacts& c = snapshot.contacts[p];
    const std::uint32_t used = std::min(c.pairs[3], kContactSlots);
    for (std::uint32_t k = 0; k < used; ++k) {
      for (int axis = 0; axis < 3; ++axis) {
        const float spring = std::bit_cast<float>(c.slots[k][axis]);
        requireFinite("WorldSnapshot.contacts[" + std::to_string(p) + "].slots[" +
                          std::to_string(k) + "] spring." + std::string(1, "xyz"[axis]),
                      spring);
      }
    }
  }
  for (std::size_t p = 0; p < snapshot.rolling.size(); ++p) {
    for (std::uint32_t k = 0; k < kContactSlots; ++k) {
      for (int axis = 0; axis < 3; ++axis) {
        requireFinite("WorldSnapshot.rolling[" + std::to_string(p) + "].springs[" +
                          std::to_string(k) + "]." + std::string(1, "xyz"[axis]),
                      std::bit_cast<float>(snapshot.rolling[p].springs[k][axis]));
      }
    }
  }
  for (std::size_t p = 0; p < snapshot.forces.size(); ++p) {
    const StoredForces& f = snapshot.forces[p];
    const std::string name = "WorldSnapshot.forces[" + std::to_string(p) + "].";
    for (int axis = 0; axis < 3; ++axis) {
      const std::string word(1, "xyz"[axis]);
      requireFinite(name + "force." + word, std::bit_cast<float>(f.force[axis]));
      requireFinite(name + "torque." + word, std::bit_cast<float>(f.torque[axis]));
    }
  }
}

std::uint64_t roughFloorParticles(double spacing, double hx, double hz, double radius,
                                  std::uint64_t limit) {
  // Every row holds its point at x = 0, so rows alone may already pass the limit.
  const double stepsZ = roughFloorSteps(hz, spacing);
  const double stepsX = roughFloorSteps(hx, spacing);
  if (!(2.0 * stepsZ + 1.0 <= double(limit)) || !(2.0 * stepsX + 1.0 <= double(limit))) {
    return limit + 1;
  }
  const auto nz = std::int64_t(stepsZ);
  const auto nx = std::int64_t(stepsX);
  std::uint64_t count = 0;
  for (std::int64_t z = -nz; z <= nz; ++z) {
    std::int64_t reach = nx;
    if (radius > 0.0) {
      const double pz = double(z) * spacing;
      // The widest x the builder's test keeps, found from the square root and then made exact.
      reach = std::min(
          nx,
          std::int64_t(std::floor(std::sqrt(std::max(0.0, radius * radius - pz * pz)) / spacing)));
      while (reach < nx && inRoughFloor(double(reach + 1) * spacing, pz, radius, spacing)) ++reach;
      while (reach >= 0 && !inRoughFloor(double(reach) * spacing, pz, radius, spacing)) --reach;
      if (reach < 0) continue;
    }
    count += std::uint64_t(2 * reach + 1);
    if (count > limit) return limit + 1;
  }
  return count;
}

}  // namespace sandphys::detail

namespace sandphys {

std::uint64_t roughFloorParticles(const RoughFloor& floor, float particleDiameter) {
  const double spacing = floor.spacing > 0.0f ? floor.spacing : particleDiameter;
  const double hx = floor.radius > 0.0f ? floor.radius : floor.halfExtentX;
  const double hz = floor.radius > 0.0f ? floor.radius : floor.halfExtentZ;
  return detail::roughFloorParticles(spacing, hx, hz, floor.radius,
                                     std::numeric_limits<std::uint64_t>::max() - 1);
}

}  // namespace sandphys
