#pragma once

#include <sandphys/error.h>
#include <sandphys/mesh.h>

class btCollisionShape;

namespace sandphys::bullet {

/// The surface of a Bullet collision shape as a closed triangle mesh, in the shape's own frame
/// (for a rigid body: its centre-of-mass frame), metres, collision margin included:
/// - convex shapes (box, sphere, capsule, cylinder, cone, convex hull, ...): the convex hull of
///   the shape's support points in a dense set of directions (the vertices of an icosphere), so
///   that a curved surface is followed to within `maxChordError` (m) and a polytope comes out
///   exact (its support points are its corners);
/// - compound shapes: every child's mesh moved by its child transform, merged;
/// - triangle meshes (btBvhTriangleMeshShape and the like, static in Bullet): their triangles,
///   scaled.
/// Throws sandphys::MeshError naming the shape (btCollisionShape::getName) when its kind has no
/// surface sandphys can sample (a plane is infinite: use a sandphys collider instead).
TriangleMesh shapeMesh(const btCollisionShape& shape, float maxChordError);

}  // namespace sandphys::bullet
