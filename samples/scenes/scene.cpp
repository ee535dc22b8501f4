#include "scenes/scene.h"

#include <algorithm>

#include "scenes/scene_parameters.h"

namespace sandphys::scenes {

std::string_view contactLawName(ContactLaw law) {
  return law == ContactLaw::PaperViscous ? "paper" : "hertz-mindlin";
}

std::optional<ContactLaw> contactLawFromName(std::string_view name) {
  for (ContactLaw law : {ContactLaw::HertzMindlin, ContactLaw::PaperViscous}) {
    if (name == contactLawName(law)) return law;
  }
  return std::nullopt;
}

WorldSettings Scene::settings() const {
  // parameters() hands out pointers to write through; the check only reads them.
  checkRanges(name(), const_cast<Scene&>(*this).parameters());
  WorldSettings settings = worldSettings();
  settings.contactLaw = m_contactLaw;
  settings.sleep.enabled = m_sleep;
  settings.material.rollingFriction = m_rollingFriction;
  return settings;
}

SceneSurface surfaceOf(BodyId body, const TriangleMesh& mesh, const SampledMesh& sampled,
                       BodyMaterial material) {
  SceneSurface surface{body, mesh, sampled.shape.principalRotation, material};
  const auto& com = sampled.massProperties.centreOfMass;
  const Vec3 centre{float(com[0]), float(com[1]), float(com[2])};
  for (Vec3& vertex : surface.mesh.vertices) vertex -= centre;
  return surface;
}

SceneView Scene::view(const std::optional<SceneBounds>& contents) const {
  return {contents ? *contents : bounds()};
}

std::optional<SceneBounds> contentsOf(const Scene& scene, const World& world) {
  const std::vector<BodyState> bodies = world.readBodies();
  const float radius = 0.5f * world.settings().particleDiameter;
  std::optional<SceneBounds> box;
  for (const ParticleState& particle : world.readParticles()) {
    const BodyState& body = bodies[particle.body.index];
    if (!body.alive || body.motion == Motion::Static || !scene.contains(body.position)) continue;
    const Vec3 lo = particle.position - Vec3{radius, radius, radius};
    const Vec3 hi = particle.position + Vec3{radius, radius, radius};
    if (!box) box = SceneBounds{lo, hi};
    box->min = {std::min(box->min.x, lo.x), std::min(box->min.y, lo.y), std::min(box->min.z, lo.z)};
    box->max = {std::max(box->max.x, hi.x), std::max(box->max.y, hi.y), std::max(box->max.z, hi.z)};
  }
  return box;
}

bool runUntilFinished(Scene& scene, World& world, float frameDt, double maxSeconds) {
  while (!scene.finished() && world.simulatedTime() < maxSeconds) {
    const StepReport report = scene.step(world, frameDt);
    scene.update(world, report, world.simulatedTime());
  }
  return scene.finished();
}

}  // namespace sandphys::scenes
