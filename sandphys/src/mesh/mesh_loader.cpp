#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#include <cmath>
#include <cstdint>
#include <system_error>
#include <unordered_map>

#include "mesh/mesh_checks.h"
#include "sandphys/mesh.h"

namespace sandphys {
namespace {

using mesh_detail::throwMeshError;

// Welds vertices whose positions are bitwise equal, keeping the order of first appearance so
// that the result does not depend on hashing.
class VertexWelder {
 public:
  explicit VertexWelder(TriangleMesh& mesh) : m_mesh(mesh) {}

  std::uint32_t add(const Vec3& v) {
    auto [it, inserted] =
        m_index.try_emplace(mesh_detail::PositionKey(v), std::uint32_t(m_mesh.vertices.size()));
    if (inserted) m_mesh.vertices.push_back(v);
    return it->second;
  }

 private:
  TriangleMesh& m_mesh;
  std::unordered_map<mesh_detail::PositionKey, std::uint32_t, mesh_detail::PositionKeyHash> m_index;
};

struct MergeCounts {
  std::size_t meshes = 0;
  std::size_t pointsAndLines = 0;  // faces dropped because they have fewer than 3 corners
};

// Appends every mesh of `node` and its children, with the accumulated node transform applied.
void mergeNode(const aiScene& scene, const aiNode& node, const aiMatrix4x4& parent,
               const std::string& source, VertexWelder& welder, TriangleMesh& out,
               MergeCounts& counts) {
  const aiMatrix4x4 transform = parent * node.mTransformation;
  // A mirroring transform turns outward winding inward: swap two corners to undo it.
  const bool mirrored = transform.Determinant() < 0.0f;
  for (unsigned m = 0; m < node.mNumMeshes; ++m) {
    // An importer's scene is trusted no further than it is checked: a node naming a mesh that is
    // not there, or a mesh without the arrays its counts promise, is the file's fault.
    const unsigned index = node.mMeshes[m];
    if (index >= scene.mNumMeshes || scene.mMeshes[index] == nullptr) {
      throwMeshError(source, "node '" + std::string(node.mName.C_Str()) + "' names mesh " +
                                 std::to_string(index) + ", but the scene has " +
                                 std::to_string(scene.mNumMeshes) + " meshes");
    }
    const aiMesh& mesh = *scene.mMeshes[index];
    if ((mesh.mNumVertices > 0 && mesh.mVertices == nullptr) ||
        (mesh.mNumFaces > 0 && mesh.mFaces == nullptr)) {
      throwMeshError(source, "mesh " + std::to_string(index) + " ('" + mesh.mName.C_Str() +
                                 "') lacks the vertices or faces it counts");
    }
    ++counts.meshes;
    std::vector<std::uint32_t> welded(mesh.mNumVertices);
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D p = transform * mesh.mVertices[v];
      welded[v] = welder.add({p.x, p.y, p.z});
    }
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) {
        // aiProcess_Triangulate leaves only points and lines here.
        ++counts.pointsAndLines;
        continue;
      }
      std::array<std::uint32_t, 3> tri{};
      for (unsigned k = 0; k < 3; ++k) {
        if (face.mIndices[k] >= mesh.mNumVertices) {
          throwMeshError(source, "face " + std::to_string(f) + " of mesh " +
                                     std::to_string(node.mMeshes[m]) + " ('" + mesh.mName.C_Str() +
                                     "') has vertex index " + std::to_string(face.mIndices[k]) +
                                     ", but that mesh has " + std::to_string(mesh.mNumVertices) +
                                     " vertices");
        }
        tri[k] = welded[face.mIndices[k]];
      }
      if (mirrored) std::swap(tri[1], tri[2]);
      out.triangles.push_back(tri);
    }
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c) {
    if (node.mChildren[c] == nullptr) continue;
    mergeNode(scene, *node.mChildren[c], transform, source, welder, out, counts);
  }
}

}  // namespace

TriangleMesh loadMesh(const std::filesystem::path& path) {
  const std::string source = path.string();
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(path, error);
  if (!std::filesystem::exists(status)) {
    throwMeshError(source, "the file does not exist");
  }
  if (!std::filesystem::is_regular_file(status)) {
    throwMeshError(source, "is not a regular file");
  }

  Assimp::Importer importer;
  // Join identical vertices only after the finiteness check below: assimp's join compares
  // positions, and a NaN corner makes it fold unrelated vertices together, which would hide the
  // vertex that is actually wrong.
  const aiScene* scene = importer.ReadFile(source, aiProcess_Triangulate);
  if (scene == nullptr) {
    throwMeshError(source, std::string("assimp could not read it: ") + importer.GetErrorString());
  }
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    if (scene->mMeshes[m] == nullptr || scene->mMeshes[m]->mVertices == nullptr) continue;
    const aiMesh& mesh = *scene->mMeshes[m];
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D& p = mesh.mVertices[v];
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
        throwMeshError(source, "vertex " + std::to_string(v) + " of mesh " + std::to_string(m) +
                                   " ('" + mesh.mName.C_Str() + "') = " +
                                   mesh_detail::formatPoint(p.x, p.y, p.z) + " is not finite");
      }
    }
  }
  scene = importer.ApplyPostProcessing(aiProcess_JoinIdenticalVertices);
  if (scene == nullptr || scene->mRootNode == nullptr) {
    throwMeshError(source,
                   std::string("assimp could not process it: ") + importer.GetErrorString());
  }

  TriangleMesh mesh;
  mesh.source = source;
  VertexWelder welder(mesh);
  MergeCounts counts;
  mergeNode(*scene, *scene->mRootNode, aiMatrix4x4(), source, welder, mesh, counts);
  if (mesh.triangles.empty()) {
    throwMeshError(source, "has no triangles (" + std::to_string(counts.meshes) +
                               " meshes in the scene, " + std::to_string(counts.pointsAndLines) +
                               " points or lines); a body needs a surface");
  }
  validateMesh(mesh);
  return mesh;
}

}  // namespace sandphys
