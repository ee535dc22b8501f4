#include "scenes/compression.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <string>

#include "scenes/kit/checks.h"
#include "scenes/kit/course.h"
#include "scenes/kit/geometry.h"
#include "scenes/kit/readback.h"
#include "scenes/kit/settings.h"

namespace sandphys::scenes {

namespace {

using kit::kReach;
// Height of the lattice's lowest centres above the floor's particle centres, d: the granule's
// reach, the floor particle's radius and the block's jitter.
constexpr float kClearance = 1.7f;
// Gap between the plunger's rim and the wall, d: narrower than any granule.
constexpr float kPlungerGap = 0.75f;
// The plunger starts this far above the settled pile, d, and the wall this far above the lattice.
constexpr float kPlungerStart = 1.0f;
constexpr float kHeadroom = 6.0f;
// The plunger has touched the sand once the stress under it passes this fraction of maxStress;
// until then it comes down kApproachFactor times faster than plungerSpeed.
constexpr double kContactFraction = 0.005;
constexpr double kApproachFactor = 4.0;

using C = CompressionConfig;
const auto kTable = std::to_array<kit::Param<C>>({
    {"radius", &C::radius, "d", 2.0, 1e4, "radius of the cylinder and the rough floor"},
    {"layers", &C::layers, "", 1, 1e5, "layers of the lattice the pile is dropped from"},
    {"plunger-speed", &C::plungerSpeed, "m/s", 1e-4, 10.0, "speed of the plunger"},
    {"max-stress", &C::maxStress, "Pa", 1.0, 1e9, "mean axial stress where the plunger turns"},
    // A pile dropped from a loose lattice is far looser than the paper's: under a small preload
    // the loading curve is mostly its collapse.
    {"preload", &C::preloadFraction, "", 0.0, 1.0,
     "stress that flattens the top first, as a fraction of max-stress"},
});

}  // namespace

std::span<const kit::Param<C>> Compression::table() const {
  return kTable;
}

std::uint64_t Compression::granules() const {
  return std::uint64_t(latticeSide()) * latticeSide() * m_config.layers;
}

std::uint32_t Compression::latticeSide() const {
  // A square layer of k granules (reach r) a side, spacing s, fits in the circle of radius R when
  // its half diagonal ((k - 1) s / 2 + r) √2 <= R.
  const double spacing = kDefaultGranuleSpacing;
  const double room = 2.0 * (m_config.radius / std::numbers::sqrt2 - kReach) / spacing;
  return room < 0.0 ? 0u : 1u + static_cast<std::uint32_t>(std::floor(room));
}

double Compression::area() const {
  const double r = m_config.radius * d();
  return std::numbers::pi * r * r;
}

std::vector<Vec3> Compression::plungerFace() const {
  // Only the face touches the sand: one layer on a triangular lattice as sampleMesh covers a
  // surface (no hole, and it feels smooth), odd rows half a spacing over.
  const double h = kDefaultMeshSpacing * d();
  const double rowHeight = h * std::numbers::sqrt3 / 2.0;
  const double r = (m_config.radius - kPlungerGap) * d();
  const auto rows = static_cast<std::int64_t>(std::floor(r / rowHeight));
  const auto across = static_cast<std::int64_t>(std::floor(r / h)) + 1;
  std::vector<Vec3> centres;
  for (std::int64_t j = -rows; j <= rows; ++j) {
    const double z = static_cast<double>(j) * rowHeight;
    for (std::int64_t i = -across; i <= across; ++i) {
      const double x = static_cast<double>(i) * h + (j % 2 == 0 ? 0.0 : 0.5 * h);
      if (x * x + z * z <= r * r) centres.push_back({float(x), 0.0f, float(z)});
    }
  }
  return centres;
}

SceneSurface Compression::plungerSurface(BodyId plunger, const ParticleTemplate& shape,
                                         const std::vector<Vec3>& face) const {
  // A disc one particle thick over the face's particles, about the face's centre of mass.
  Vec3 centre{};
  for (const Vec3& c : face) centre += c / float(face.size());
  const double radius = (m_config.radius - kPlungerGap) * d() + 0.5 * d();
  return {plunger, cylinderMesh(radius, d(), 64, Vec3{} - centre), shape.principalRotation,
          BodyMaterial::Metal};
}

WorldSettings Compression::worldSettings() const {
  // The lattice's top falls onto the pile like grains from an emitter at rest.
  const float blockHeight =
      (static_cast<float>(m_config.layers) * kDefaultGranuleSpacing + kClearance) * d();
  return kit::worldSettings(
      name(), d(),
      {.granules = granules(),
       .bodies = 2,
       .particles = roughFloorParticles(RoughFloor{.radius = m_config.radius * d()}, d()) +
                    plungerFace().size(),
       .maxSpeed = kit::pourGuardSpeed(0.0f, blockHeight, kit::kGravity),
       .stepsPerContact = m_config.stepsPerContact,
       .youngsModulus = m_config.youngsModulus,
       .friction = m_config.friction});
}

void Compression::build(World& world) {
  m_phase = Phase::Settling;
  m_turn = 0;
  m_curve.clear();
  m_atRest = m_atPeak = {};
  m_maxStrain = m_residualStrain = m_peakStress = m_velocity = 0.0;
  m_granuleMass = kit::granuleMass(world.settings());

  const float radius = m_config.radius * d();
  const float spacing = kDefaultGranuleSpacing * d();
  const float blockHeight = kit::blockSpan(m_config.layers, spacing);
  const float wallHeight = (kClearance + kHeadroom) * d() + blockHeight + kReach * d();
  world.addRoughFloor(RoughFloor{.center = {0.0f, 0.0f, 0.0f}, .radius = radius, .spacing = d()});
  world.addCollider(Cylinder{.base = {0.0f, 0.0f, 0.0f}, .radius = radius, .height = wallHeight});
  const Count3 lattice{latticeSide(), m_config.layers, latticeSide()};
  world.addGranules(kit::blockAbove(kClearance * d(), lattice, spacing, m_config.seed));
  // Parked above the wall until the pile has settled.
  m_bottomY = wallHeight + d();
  const std::vector<Vec3> face = plungerFace();
  // A kinematic body: its mass only has to be valid.
  const ParticleTemplate plunger =
      makeParticleTemplate(face, d(), WorldSettings{}.material.density);
  m_plunger = world.addBody(
      plunger, BodyDesc{.position = {0.0f, float(m_bottomY), 0.0f}, .motion = Motion::Kinematic});
  m_surfaces = {plungerSurface(m_plunger, plunger, face)};
  // Calm means nothing until the lattice has fallen onto the floor and slid a while.
  const double landing =
      1.5 * kit::fallTime(blockHeight + kClearance * d(), 0.0, length(world.settings().gravity));
  m_settle = {0.0, landing, landing + m_config.maxSettleSeconds};
}

void Compression::enter(Phase phase, double simTime) {
  // The plunger's direction in each phase, in units of plungerSpeed.
  constexpr std::array<double, 7> kDirection{0.0, -kApproachFactor, -1.0, 1.0, -1.0, 1.0, 0.0};
  m_phase = phase;
  m_moveFromY = m_bottomY;
  m_moveStart = simTime;
  m_velocity = kDirection[static_cast<std::size_t>(phase)] * m_config.plungerSpeed;
}

void Compression::update(World& world, const StepReport& report, double simTime) {
  if (m_phase == Phase::Done) return;
  if (m_phase == Phase::Settling) {
    const bool calm = kit::granulesCalm(report, static_cast<std::uint32_t>(granules()),
                                        m_granuleMass, m_config.settleSpeed);
    if (!m_settle.over(calm, simTime)) return;
    m_atRest = {simTime, world.readContacts(), world.readBodies()};
    float top = 0.0f;
    for (const BodyState& body : kit::granulesIn(m_atRest.bodies)) {
      top = std::max(top, body.position.y);
    }
    m_bottomY = top + (kReach + kPlungerStart) * d();
    enter(Phase::Approach, simTime);
    world.takeBodyForces();  // from now on
  } else {
    const std::optional<BodyForce> force = kit::takeForceOn(world, m_plunger);
    const double stress = (force ? force->meanForce().y : 0.0) / area();
    const float max = m_config.maxStress;  // float: the preload's threshold is a float product
    const auto strain = [&] { return (m_contactY - m_bottomY) / m_height; };  // from Loading on
    if (m_phase == Phase::Loading || m_phase == Phase::Unloading) {
      m_curve.push_back({strain(), stress});
    }
    if (m_phase == Phase::Unloading) m_residualStrain = strain();  // until the stress is zero
    const bool turn = m_phase == Phase::Approach  ? stress > kContactFraction * max
                      : m_phase == Phase::Preload ? stress >= m_config.preloadFraction * max
                      : m_phase == Phase::Loading ? stress >= max
                                                  : stress <= 0.0;  // Easing, Unloading
    if (turn && m_phase == Phase::Easing) {
      // The lowest height without compression: the experiment starts here.
      m_contactY = m_bottomY;
      m_height = m_contactY - 0.5 * d();  // above the floor's particles
      m_curve.push_back({0.0, 0.0});
    } else if (turn && m_phase == Phase::Loading) {
      m_peakStress = stress;
      m_maxStrain = strain();
      m_turn = m_curve.size();
      m_atPeak = {simTime, world.readContacts(), world.readBodies()};
    }
    if (turn) enter(static_cast<Phase>(static_cast<int>(m_phase) + 1), simTime);
  }
  m_bottomY = m_moveFromY + m_velocity * (simTime - m_moveStart);
  world.setBodyState(m_plunger, BodyDesc{.position = {0.0f, float(m_bottomY), 0.0f},
                                         .velocity = {0.0f, float(m_velocity), 0.0f},
                                         .motion = Motion::Kinematic});
}

double Compression::recoveredFraction() const {
  return m_maxStrain > 0.0 ? (m_maxStrain - m_residualStrain) / m_maxStrain : 0.0;
}

std::string Compression::status() const {
  constexpr std::array<const char*, 7> kNames{"settling", "approach",  "preload", "easing",
                                              "loading",  "unloading", "done"};
  std::string text = kNames[static_cast<std::size_t>(m_phase)];
  if (m_phase == Phase::Loading || m_phase == Phase::Unloading) {
    text += ": " + kit::numberText(std::round(m_curve.back()[1] / 100.0) / 10.0) + " kPa";
  }
  return text;
}

bool Compression::contains(const Vec3& centre) const {
  return centre.y >= 0.0f && std::hypot(centre.x, centre.z) <= m_config.radius * d();
}

std::vector<SceneMetric> Compression::metrics(std::span<const BodyState> /*bodies*/) const {
  return {
      {"granules", static_cast<double>(granules())},
      {"pile_height_d", m_height / d()},
      {"peak_stress_pa", m_peakStress},
      {"max_strain", m_maxStrain},
      {"residual_strain", m_residualStrain},
      {"recovered_fraction", recoveredFraction()},
      {"contacts_at_rest", static_cast<double>(m_atRest.contacts.size())},
      {"contacts_at_peak", static_cast<double>(m_atPeak.contacts.size())},
  };
}

std::vector<SceneSeries> Compression::series() const {
  return {{.name = "stress_strain",
           .points = m_curve,
           .derived = {{"max_strain", m_maxStrain},
                       {"residual_strain", m_residualStrain},
                       {"recovered_fraction", recoveredFraction()}}}};
}

SceneBounds Compression::bounds() const {
  const float r = m_config.radius * d();
  const float top = (kClearance + kHeadroom + 4.0f) * d() +
                    static_cast<float>(m_config.layers) * kDefaultGranuleSpacing * d();
  return {{-r, 0.0f, -r}, {r, top, r}};
}

}  // namespace sandphys::scenes
