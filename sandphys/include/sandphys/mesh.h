#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "sandphys/body.h"
#include "sandphys/math.h"

namespace sandphys {

/// An indexed triangle mesh, as loaded from a file or built in code. Coordinates are metres in the
/// body's own frame (mesh files carry no unit: 1 in the file is 1 m).
struct TriangleMesh {
  /// Vertex positions, m; finite.
  std::vector<Vec3> vertices;
  /// Vertex indices of each triangle, counter-clockwise seen from outside the solid (the
  /// convention of OBJ, STL, PLY and glTF); each < vertices.size().
  std::vector<std::array<std::uint32_t, 3>> triangles;
  /// Where the mesh came from (a file path, or a name for a mesh built in code); error messages
  /// and warnings quote it.
  std::string source;
};

/// Loads every mesh of a file with assimp (OBJ, STL, PLY, glTF/GLB, and the other formats assimp
/// reads), applies each node's accumulated transform (a mirroring transform keeps the triangles
/// wound outward), triangulates polygons, drops points and lines, and merges everything into one
/// mesh whose vertices are welded where their positions are bitwise equal (so that the faces of
/// an STL file, or the parts of a file split by material, share their corners). A mesh referenced
/// by several nodes appears once per node. The result has passed validateMesh. Throws MeshError
/// naming the file: missing or unreadable file, assimp's own failure (with its message), no
/// triangles, non-finite vertices, indices out of range, no triangle with an area. assimp's
/// importers trust the sizes a file states: a damaged file may make them allocate what it claims
/// (assimp's own test file invalid/OutOfMemory.off asks for 16 GB, and assimp aborts when that
/// succeeds); load files you do not trust in a process with a memory limit, as the corpus tests
/// do (a failed allocation there is an assimp failure, a MeshError).
TriangleMesh loadMesh(const std::filesystem::path& path);

/// The checks every mesh must pass before it makes a body; loadMesh and sampleMesh run them, so a
/// mesh built in code gets the same ones. Throws MeshError naming TriangleMesh::source and the
/// problem: no triangles; a non-finite vertex (its index and value); a triangle index out of range
/// (the triangle, the index and the vertex count); every triangle of zero area (within float
/// rounding: twice its area <= 1e-6 of its longest edge squared).
void validateMesh(const TriangleMesh& mesh);

/// How the triangles of a mesh fit together along their edges. Vertices are matched by position,
/// so a mesh that repeats a corner for each face is judged by its shape, not its indexing.
struct MeshEdges {
  /// Distinct undirected edges (a triangle that repeats a corner adds none: its edges cancel).
  std::size_t edges = 0;
  /// Edges used by one triangle only, or by an odd number: the rims of holes.
  std::size_t openEdges = 0;
  /// Edges used an even number of times but not as often in each direction: neighbouring
  /// triangles wound inconsistently (one of them faces the wrong way).
  std::size_t misorientedEdges = 0;
  /// True when every edge is used as often in one direction as in the other (each by a pair of
  /// oppositely wound triangles, or by two such pairs where two solids touch along an edge):
  /// the mesh is the boundary of a solid, and the divergence theorem gives that solid's volume.
  bool closed() const { return edges > 0 && openEdges == 0 && misorientedEdges == 0; }
};

/// Counts the edges that keep a mesh from being closed. Runs validateMesh first.
MeshEdges analyseEdges(const TriangleMesh& mesh);

/// Total area of the triangles, m².
double surfaceArea(const TriangleMesh& mesh);

/// The solid a closed mesh bounds, by the divergence theorem.
struct SolidProperties {
  /// Volume, m³; > 0.
  double volume = 0.0;
  /// Mass (density · volume), centre of mass and inertia tensor about it, exact for the
  /// polyhedron up to double rounding.
  MassProperties massProperties;
  /// The triangles were wound inward (clockwise seen from outside), so that the signed volume
  /// came out negative; the solid they enclose is used all the same.
  bool woundInward = false;
};

/// Volume, centre of mass and full inertia tensor of the homogeneous solid bounded by a closed
/// mesh, of `density` kg/m³ (> 0): each triangle spans a signed tetrahedron with a reference point,
/// whose volume, first and second moments have closed forms; the signed sums are the solid's.
/// Parts that overlap count twice (a file of two interpenetrating closed shells). Throws MeshError
/// when the mesh fails validateMesh, is not closed (analyseEdges) or encloses no volume.
SolidProperties solidProperties(const TriangleMesh& mesh, double density);

/// The box [lo, hi] (m) as 12 outward-wound triangles on its 8 corners; source "box".
TriangleMesh boxMesh(Vec3 lo, Vec3 hi);

/// A sphere of `radius` (m, > 0) about `centre`: an icosahedron whose triangles are split in four
/// `subdivisions` times (0..8), every vertex pushed out onto the sphere: 20 · 4^subdivisions
/// outward-wound triangles, whose facets sag at most about radius · (1.107 / 2^subdivisions)² / 8
/// inside the sphere; source "icosphere".
TriangleMesh icosphereMesh(double radius, int subdivisions, Vec3 centre = {});

/// A closed upright cylinder of `radius` and `height` (m, > 0) about `centre`, its axis along y:
/// `segments` (3..4096) side quads on two rings, each cut in two triangles, and a fan of
/// `segments` triangles on each cap around a centre vertex, all wound outward; the ring's
/// polygon is inscribed in the circle. Source "cylinder".
TriangleMesh cylinderMesh(double radius, double height, int segments, Vec3 centre = {});

/// Default largest distance between neighbouring surface samples, in particle diameters d (see
/// MeshSampling::spacing for the geometry behind it).
inline constexpr float kDefaultMeshSpacing = 0.8f;

/// How sampleMesh places particles. Plain aggregate: designated initialisers work on it.
struct MeshSampling {
  /// Largest distance h between neighbouring surface samples, m; 0 means kDefaultMeshSpacing
  /// particle diameters. In (0, √3 d), d the particle diameter.
  ///
  /// The surface is covered by a lattice whose cells are triangles with edges <= h, so every
  /// point of the surface lies within h/√3 of a particle centre (the covering radius of such a
  /// triangle: its circumradius when acute, less otherwise). A sand particle of diameter d gets
  /// through only where the samples leave most room: at the worst point its centre is h/√3 from
  /// three samples, an overlap of d - h/√3 with each, which vanishes at h = √3 d. The default
  /// h = 0.8 d puts the worst point 0.46 d from a sample: the spheres of the samples (radius d/2)
  /// cover the whole surface with no hole (that needs h <= √3/2 d = 0.87 d); a grain must overlap
  /// three samples by 0.54 d each to get through, more than five times the d/10 at which the
  /// penetration guard clamps; a grain resting over the worst point sits only
  /// d - √(d² - (0.46 d)²) = 0.11 d lower than over a sample, so the surface feels smooth; and
  /// neighbouring samples are at most 0.8 d apart. The particle count grows as 1/h².
  float spacing = 0.0f;
  /// Also fill the inside with particles: the points of a cubic lattice of spacing h, centred on
  /// the mesh's bounding box (a symmetric mesh gets a symmetric filling), that lie inside the mesh
  /// and at least h/2 from every surface sample. Inside means a nonzero winding number, counted
  /// along one ray in +x per lattice row (a point inside two overlapping closed parts is inside
  /// once). Grains that hit hard enough to get through the surface layer still meet particles
  /// then; it costs about volume/h³ particles, and the mass properties stay those of the solid.
  /// Needs a closed mesh (MeshError otherwise).
  bool fillVolume = false;
  /// Density of the body, kg/m³; > 0. Used when `mass` is 0.
  float density = 2600.0f;
  /// Mass of the body, kg; >= 0. Above 0 it overrides the density: the mass properties are
  /// scaled to it.
  float mass = 0.0f;
  /// Largest particle count sampleMesh may produce; > 0. A finer spacing or a larger mesh is
  /// refused with CapacityExceeded before memory runs out.
  std::uint32_t maxParticles = 1u << 20;
};

/// Particles of one sampled body above which sampleMesh warns: a body that is not a granule is
/// integrated by one workgroup every substep (on llvmpipe, one CPU core), so its particles cost
/// serially what the sand's cost in parallel.
inline constexpr std::size_t kLargeBodyWarningParticles = 16384;

/// A mesh turned into a body shape, with what was measured on the way.
struct SampledMesh {
  /// The body shape for World::addBody: particles of the given diameter, in the principal frame
  /// of the mass properties below.
  ParticleTemplate shape;
  /// The particle centres in the mesh's own frame, m, in the order of shape.offsets.
  std::vector<Vec3> centres;
  /// Particles on the surface; the rest (fillVolume) come after them.
  std::size_t surfaceParticles = 0;
  /// Volume of the solid, m³; 0 for an open mesh.
  double volume = 0.0;
  /// Area of the triangles, m².
  double surfaceArea = 0.0;
  /// The mesh bounds a solid (MeshEdges::closed).
  bool closed = false;
  /// Mass, centre of mass (in the mesh's frame) and inertia that the shape was built from.
  MassProperties massProperties;
  /// What the caller should know: an open mesh and its fallback, inward winding, more particles
  /// than kLargeBodyWarningParticles. Each is also logged once (setLogHandler), when sampleMesh
  /// finds it.
  std::vector<std::string> warnings;
};

/// Point-samples a mesh into particles of diameter `particleDiameter` (m, > 0; the World's) for a
/// large rigid body. Each triangle is subdivided into equal sub-triangles with edges <= h (see
/// MeshSampling::spacing), and their corners become particle centres; corners that triangles
/// share (closer than h/1000) become one particle, and a corner is left out where an earlier
/// particle already keeps the surface around it within h/√3 of a centre. So the count follows
/// the area and the spacing (about 1.2 · area / h² for a lattice, up to about 2.3 times that for a
/// mesh much finer than h), never the triangle count. The result is deterministic: the same mesh
/// and options give the same particles in the same order.
///
/// Mass properties: for a closed mesh (MeshEdges::closed), those of the homogeneous solid it
/// bounds (solidProperties), at MeshSampling::density or scaled to MeshSampling::mass; the
/// particles only carry the contacts. For an open mesh there is no solid: a warning says so, and
/// the particles themselves are the body, as makeParticleTemplate sums them (solid spheres of
/// diameter d), scaled to MeshSampling::mass if given, else each particle weighing
/// density · πd³/6 (a thin shell, far lighter than a solid of the same outline).
///
/// Throws MeshError (validateMesh; fillVolume on an open mesh), InvalidArgument (diameter,
/// spacing, density, mass) and CapacityExceeded (more than MeshSampling::maxParticles).
SampledMesh sampleMesh(const TriangleMesh& mesh, float particleDiameter,
                       const MeshSampling& options = {});

}  // namespace sandphys
