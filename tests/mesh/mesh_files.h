#pragma once

#include <sandphys/sandphys.h>

#include <filesystem>
#include <string>

namespace sandphys::mesh_testing {

/// A fresh, empty directory for one test's files (under the system's temporary directory, named
/// after the test and the process), removed when this goes out of scope.
class ScratchDirectory {
 public:
  ScratchDirectory();
  ~ScratchDirectory();
  ScratchDirectory(const ScratchDirectory&) = delete;
  ScratchDirectory& operator=(const ScratchDirectory&) = delete;

  const std::filesystem::path& path() const { return m_path; }
  /// Writes `text` to the file `name` in this directory and returns its path.
  std::filesystem::path write(const std::string& name, const std::string& text) const;

 private:
  std::filesystem::path m_path;
};

/// The box [lo, hi] in each format, as a modeller would export it: OBJ and PLY with quads (the
/// loader triangulates them), ASCII STL with three corners per facet (the loader welds them).
std::string boxObj(Vec3 lo, Vec3 hi);
std::string boxStl(Vec3 lo, Vec3 hi);
std::string boxPly(Vec3 lo, Vec3 hi);

/// A glTF 2.0 file whose buffer (the box [lo, hi] as 8 positions and 36 indices) is embedded as
/// base64. `meshes` and `nodes` are the JSON arrays of those names; the meshes' primitive is
/// written `PRIMITIVE` in them and refers to that buffer.
std::string boxGltf(Vec3 lo, Vec3 hi, const std::string& meshes, const std::string& nodes,
                    const std::string& sceneNodes);

}  // namespace sandphys::mesh_testing
