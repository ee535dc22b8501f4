#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "scenes/scene.h"

namespace sandphys::render {

/// One vertex of the bodies' surfaces, as shaders/render/surface.vert reads it: in the body's
/// principal frame about its centre of mass, so that the World's pose on the GPU places it.
struct SurfaceVertex {
  float x, y, z;
  std::uint32_t body;      ///< the body's slot (BodyId::index)
  float nx, ny, nz;        ///< the triangle's outward normal
  std::uint32_t material;  ///< scenes::BodyMaterial
};

/// Triangles (no index buffer) of every surface, each flat-shaded with its own normal.
std::vector<SurfaceVertex> buildSurfaceMesh(std::span<const scenes::SceneSurface> surfaces);

/// A hash of everything buildSurfaceMesh reads, so that the renderer uploads the surfaces again
/// only when they changed (a scene rebuilt, another scene).
std::uint64_t surfacesHash(std::span<const scenes::SceneSurface> surfaces);

}  // namespace sandphys::render
