#pragma once

#include <Eigen/Core>
#include <vector>

#include <sandphys/colliders.h>

namespace sandphys::render {

/// One vertex of a collider mesh, as shaders/render/mesh.vert reads it.
struct MeshVertex {
  float x, y, z;
  /// 0: drawn from both sides; 1 (cutaway): the side facing the eye is not drawn (thin walls,
  /// container boxes); 2 (one-sided): drawn only from the side the normal points to (a plane
  /// seen from inside its solid half-space would hide the whole scene).
  float cutaway;
  float nx, ny, nz;
  float unused;
};

/// Triangles (no index buffer) for every collider, with outward normals. A plane becomes its cut
/// through the box [clipLo, clipHi] (m), nothing when it misses it.
std::vector<MeshVertex> buildColliderMesh(const std::vector<ColliderShape>& colliders,
                                          const Eigen::Vector3f& clipLo,
                                          const Eigen::Vector3f& clipHi);

}  // namespace sandphys::render
