#include "export/lammps_scene.h"

#include <GL/glew.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <bit>
#include <limits>

#include "core/gpu_layout.h"
#include "core/world_access.h"
#include "gl/gl_check.h"

namespace sandphys::detail {

namespace {

Eigen::Vector3d vec(const GpuVec4& v) {
  return {v.x, v.y, v.z};
}

Vec3d array(const Eigen::Vector3d& v) {
  return {v.x(), v.y(), v.z()};
}

}  // namespace

LammpsScene gatherLammpsScene(const World& world) {
  const World::Impl& w = WorldAccess::impl(world);
  w.gpu->makeCurrent();
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  const auto position = w.buffers[kBodyPosition].downloadArray<GpuVec4>(w.bodyCount);
  const auto orientation = w.buffers[kBodyOrientation].downloadArray<GpuVec4>(w.bodyCount);
  const auto velocity = w.buffers[kBodyVelocity].downloadArray<GpuVec4>(w.bodyCount);
  const auto spin = w.buffers[kBodyAngularVelocity].downloadArray<GpuVec4>(w.bodyCount);
  const auto inertia = w.buffers[kBodyInertia].downloadArray<GpuVec4>(w.bodyCount);
  const auto info = w.buffers[kBodyInfo].downloadArray<GpuUVec4>(w.bodyCount);
  const auto local = w.buffers[kParticleLocal].downloadArray<GpuVec4>(w.particleCount);
  gl::check("exportLammps");

  LammpsScene scene;
  std::vector<LammpsAtom> frozen;
  scene.lo.fill(std::numeric_limits<double>::infinity());
  scene.hi.fill(-std::numeric_limits<double>::infinity());
  const double particleMass = w.model.particleMass;
  for (std::uint32_t b = 0; b < w.bodyCount; ++b) {
    if ((info[b].z & kBodyAlive) == 0) {
      ++scene.deadBodies;
      continue;
    }
    const GpuVec4& q = orientation[b];
    const Eigen::Matrix3d rotation = Eigen::Quaterniond(q.w, q.x, q.y, q.z).toRotationMatrix();
    const Eigen::Vector3d centre = vec(position[b]);
    const Motion motion = w.bodyMotions[b];
    const bool clump = motion == Motion::Dynamic;
    const std::uint32_t first = info[b].x;
    const std::uint32_t count = info[b].y;
    if (clump) {
      const double mass = inertia[b].w;
      const Eigen::Matrix3d tensor = rotation * vec(inertia[b]).asDiagonal() * rotation.transpose();
      LammpsClump c;
      c.slot = b;
      c.mass = mass;
      c.centre = array(centre);
      c.inertia = {tensor(0, 0), tensor(1, 1), tensor(2, 2),
                   tensor(0, 1), tensor(0, 2), tensor(1, 2)};
      c.velocity = array(vec(velocity[b]));
      c.angularMomentum = array(tensor * vec(spin[b]));
      scene.clumps.push_back(c);
      if (w.sleep.enabled && std::bit_cast<std::uint32_t>(velocity[b].w) >= w.sleep.substeps &&
          (info[b].z & kBodyGranule) != 0) {
        ++scene.sleepingGranules;
      }
    } else {
      ++(motion == Motion::Static ? scene.staticBodies : scene.kinematicBodies);
    }
    for (std::uint32_t p = first; p < first + count; ++p) {
      const Eigen::Vector3d at = centre + rotation * vec(local[p]);
      LammpsAtom atom{array(at), 0u, particleMass};
      if (clump) {
        atom.molecule = static_cast<std::uint32_t>(scene.clumps.size());
        atom.mass = inertia[b].w / count;
        scene.largestClumpRadius = std::max(scene.largestClumpRadius, (at - centre).norm());
        scene.atoms.push_back(atom);
      } else {
        frozen.push_back(atom);
      }
      for (int k = 0; k < 3; ++k) {
        scene.lo[k] = std::min(scene.lo[k], at[k]);
        scene.hi[k] = std::max(scene.hi[k], at[k]);
      }
    }
  }
  scene.clumpAtoms = static_cast<std::uint32_t>(scene.atoms.size());
  scene.atoms.insert(scene.atoms.end(), frozen.begin(), frozen.end());
  return scene;
}

}  // namespace sandphys::detail
