#pragma once

#include <array>
#include <vector>

#include "sandphys/math.h"

namespace sandphys {

/// Who moves a body.
enum class Motion : unsigned {
  Dynamic = 0,    ///< integrated by sandphys from sand forces and gravity
  Kinematic = 1,  ///< pose and velocities set from outside; sand force still summed
  Static = 2,     ///< never moves (rough floors, fixed obstacles)
};

/// A rigid arrangement of equal particles, in its principal frame: the centre of mass is at the
/// origin and the inertia tensor is diagonal. Built by makeParticleTemplate or makeBodyTemplate
/// (sampleMesh uses the latter), never typed in.
struct ParticleTemplate {
  /// Particle centres relative to the centre of mass, in the principal frame, m.
  std::vector<Vec3> offsets;
  /// Total mass, kg.
  float mass = 0.0f;
  /// Principal moments of inertia about the centre of mass, kg·m².
  Vec3 principalInertia{};
  /// Rotation from the principal frame to the frame the particle centres were given in. A body
  /// spawned with orientation q is stored with orientation q · principalRotation.
  Quat principalRotation{};
  /// Largest distance of a particle centre from the centre of mass, m.
  float boundingRadius = 0.0f;
  /// For a surface sampled into particles (sampleMesh): the sampling spacing h, m, so that
  /// World::addBody can check that a granule meeting it does not get between the samples
  /// (surfacePassOverlap). 0 for a cluster of particles that is not a sampled surface.
  float surfaceSpacing = 0.0f;
};

/// Builds a template from particle centres (m, any frame) of diameter `particleDiameter` (m):
/// mass = count · density · πd³/6 unless `mass` > 0 is given (kg); inertia = solid spheres plus
/// parallel-axis terms (scaled to the mass), diagonalised with Eigen. Throws InvalidArgument for
/// an empty list, non-finite centres or non-positive diameter/density.
ParticleTemplate makeParticleTemplate(const std::vector<Vec3>& centres, float particleDiameter,
                                      float density, float mass = 0.0f);

/// Mass, centre of mass and inertia tensor of a rigid body, in the frame its particle centres are
/// given in. Double precision: sampleMesh computes them exactly from a closed mesh, and a body far
/// from the origin of its mesh file would lose its small moments in float.
struct MassProperties {
  /// Total mass, kg; finite and > 0.
  double mass = 0.0;
  /// Centre of mass, m; finite.
  std::array<double, 3> centreOfMass{};
  /// Inertia tensor about the centre of mass, kg·m², row-major. Must be symmetric and physical:
  /// positive definite, and no principal moment larger than the sum of the other two.
  std::array<std::array<double, 3>, 3> inertia{};
};

/// Builds a template whose mass, centre of mass and inertia are given rather than summed from
/// the particles: the particles only carry the contacts (a mesh-sampled shell, say), while the
/// body moves like the solid they outline. The tensor is diagonalised with Eigen; the offsets are
/// `centres` (m, in the frame of `massProperties`) relative to the centre of mass, in the principal
/// frame. Throws InvalidArgument for an empty list, non-finite centres, a non-positive mass or an
/// inertia tensor that is not symmetric, positive definite and within the triangle inequality.
ParticleTemplate makeBodyTemplate(const std::vector<Vec3>& centres,
                                  const MassProperties& massProperties);

/// The sand granule of the paper: 4 particles of diameter d touching at the corners of a
/// regular tetrahedron of edge d.
ParticleTemplate tetrahedronTemplate(float particleDiameter, float density);

/// Initial state of a body.
struct BodyDesc {
  Vec3 position{};         ///< centre of mass, m
  Quat orientation{};      ///< orientation of the template's original frame
  Vec3 velocity{};         ///< m/s
  Vec3 angularVelocity{};  ///< rad/s, world frame
  Motion motion = Motion::Dynamic;
};

}  // namespace sandphys
