#include "render/surface_mesh.h"

namespace sandphys::render {

std::vector<SurfaceVertex> buildSurfaceMesh(std::span<const scenes::SceneSurface> surfaces) {
  std::vector<SurfaceVertex> out;
  for (const scenes::SceneSurface& surface : surfaces) {
    // The World turns the principal frame; the mesh is given in the template's own frame.
    const Quat toPrincipal = conjugate(surface.principalRotation);
    const auto material = static_cast<std::uint32_t>(surface.material);
    for (const auto& triangle : surface.mesh.triangles) {
      Vec3 corners[3];
      for (int k = 0; k < 3; ++k) {
        corners[k] = rotate(toPrincipal, surface.mesh.vertices[triangle[k]]);
      }
      const Vec3 normal = normalized(cross(corners[1] - corners[0], corners[2] - corners[0]));
      for (const Vec3& c : corners) {
        out.push_back({c.x, c.y, c.z, surface.body.index, normal.x, normal.y, normal.z, material});
      }
    }
  }
  return out;
}

std::uint64_t surfacesHash(std::span<const scenes::SceneSurface> surfaces) {
  // FNV-1a over the bytes of every field.
  std::uint64_t hash = 14695981039346656037ull;
  auto mix = [&](const void* data, std::size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; ++i) hash = (hash ^ p[i]) * 1099511628211ull;
  };
  for (const scenes::SceneSurface& s : surfaces) {
    mix(&s.body, sizeof s.body);
    mix(&s.principalRotation, sizeof s.principalRotation);
    mix(&s.material, sizeof s.material);
    mix(s.mesh.vertices.data(), s.mesh.vertices.size() * sizeof(Vec3));
    mix(s.mesh.triangles.data(), s.mesh.triangles.size() * sizeof s.mesh.triangles[0]);
    const std::size_t sizes[2] = {s.mesh.vertices.size(), s.mesh.triangles.size()};
    mix(sizes, sizeof sizes);
  }
  return hash;
}

}  // namespace sandphys::render
