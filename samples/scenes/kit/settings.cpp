#include "scenes/kit/settings.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "scenes/scene.h"

namespace sandphys::scenes::kit {

namespace {

constexpr float kPourGuardMargin = 1.25f;
constexpr float kFallGuardMargin = 1.1f;

}  // namespace

float pourGuardSpeed(float speed, float height, float g) {
  const float impact = std::sqrt(speed * speed + 2.0f * g * height);
  return std::max(kMinGuardSpeed, kPourGuardMargin * impact);
}

float fallGuardSpeed(float height) {
  return std::max(kMinGuardSpeed, kFallGuardMargin * std::sqrt(2.0f * kGravity * height));
}

void reserveExactly(WorldSettings& settings, std::string_view scene, std::uint64_t granules,
                    std::uint64_t bodies, std::uint64_t particles) {
  constexpr std::uint64_t kLimit = std::numeric_limits<std::uint32_t>::max();
  const std::uint64_t allParticles = 4 * granules + particles;
  if (granules > kLimit || allParticles > kLimit) {
    throw InvalidArgument(std::string(scene) + ": " + std::to_string(granules) + " granules and " +
                          std::to_string(particles) +
                          " particles of other bodies are more than a World can index (" +
                          std::to_string(kLimit) + " particles)");
  }
  settings.maxBodies = static_cast<std::uint32_t>(granules + bodies);
  settings.maxParticles = static_cast<std::uint32_t>(allParticles);
}

float granuleMass(const WorldSettings& settings) {
  return tetrahedronTemplate(settings.particleDiameter, settings.material.density).mass;
}

WorldSettings worldSettings(std::string_view scene, float d, const SettingsRule& rule) {
  WorldSettings settings;
  settings.particleDiameter = d;
  if (rule.friction) settings.material.friction = *rule.friction;
  if (rule.restitution) settings.material.restitution = *rule.restitution;
  reserveExactly(settings, scene, rule.granules, rule.bodies, rule.particles);
  settings.statsEachFrame = rule.statsEachFrame;
  settings.maxSpeed = rule.maxSpeed;
  settings.stepsPerContact = rule.stepsPerContact;
  settings.material.youngsModulus = sceneYoungsModulus(settings, rule.youngsModulus);
  return settings;
}

float sceneYoungsModulus(const WorldSettings& settings, float youngsModulus) {
  if (youngsModulus > 0.0f) return youngsModulus;
  return static_cast<float>(
      youngsModulusForPeakOverlap(settings, kScenePeakOverlap * settings.particleDiameter));
}

}  // namespace sandphys::scenes::kit
