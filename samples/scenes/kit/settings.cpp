#include "scenes/kit/settings.h"

#include "scenes/kit/geometry.h"
#include "scenes/scene.h"

namespace sandphys::scenes::kit {

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

}  // namespace sandphys::scenes::kit
