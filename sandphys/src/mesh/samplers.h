#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <string>
#include <vector>

#include "mesh/point_grid.h"
#include "sandphys/mesh.h"

namespace sandphys::mesh_detail {

/// Samples of the surface of a validated mesh: each triangle with an area, first halved along its
/// longest edge until no piece is more elongated than a right isosceles triangle, is cut into
/// equal sub-triangles with edges <= `spacing` (m), whose corners are the samples; a corner
/// within spacing/1000 of an earlier sample is the same sample, and so is one within
/// spacing/√3 - c of an earlier sample, c the covering radius of its sub-triangles (so that every
/// point of the surface stays within spacing/√3 of a sample, and a mesh finer than the spacing
/// is not sampled at every vertex). Triangle by triangle, in mesh order.
/// The grid's cells are spacing/√3 wide. Throws CapacityExceeded past `maxParticles`.
PointGrid sampleSurface(const TriangleMesh& mesh, double spacing, std::size_t maxParticles);

/// Points of a cubic lattice of `spacing` (m), centred on the mesh's bounding box, that lie
/// inside the closed mesh (nonzero winding number, from a ray cast along +x per lattice row) and
/// at least spacing/2 from every surface sample; ordered by z, then y, then x. Throws
/// CapacityExceeded when they and the surface samples exceed `maxParticles`.
std::vector<Eigen::Vector3d> sampleInterior(const TriangleMesh& mesh, double spacing,
                                            const PointGrid& surface, std::size_t maxParticles);

/// Throws CapacityExceeded for a mesh whose sampling needs more than `maxParticles` particles;
/// `estimate` > 0 is quoted as the count it would need.
[[noreturn]] void throwTooManyParticles(const std::string& source, double spacing,
                                        std::size_t maxParticles, double estimate);

}  // namespace sandphys::mesh_detail
