#include "mesh/mesh_files.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/Geometry>

#include <bit>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <vector>

#include "mesh/mesh_shapes.h"

namespace sandphys::mesh_testing {
namespace {

std::string base64(const std::vector<std::uint8_t>& bytes) {
  static const char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::uint32_t chunk = std::uint32_t(bytes[i]) << 16 |
                                (i + 1 < bytes.size() ? std::uint32_t(bytes[i + 1]) << 8 : 0u) |
                                (i + 2 < bytes.size() ? std::uint32_t(bytes[i + 2]) : 0u);
    out += kAlphabet[(chunk >> 18) & 63];
    out += kAlphabet[(chunk >> 12) & 63];
    out += i + 1 < bytes.size() ? kAlphabet[(chunk >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kAlphabet[chunk & 63] : '=';
  }
  return out;
}

template <typename T>
void append(std::vector<std::uint8_t>& bytes, T value) {
  static_assert(std::endian::native == std::endian::little, "glTF buffers are little-endian");
  std::uint8_t raw[sizeof(T)];
  std::memcpy(raw, &value, sizeof(T));
  bytes.insert(bytes.end(), raw, raw + sizeof(T));
}

std::string replaceAll(std::string text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at)) {
    text.replace(at, from.size(), to);
    at += to.size();
  }
  return text;
}

}  // namespace

ScratchDirectory::ScratchDirectory() {
  const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
  m_path = std::filesystem::temp_directory_path() /
           ("sandphys-mesh-" + std::string(test ? test->name() : "test") + "-" +
            std::to_string(::getpid()));
  std::filesystem::remove_all(m_path);
  std::filesystem::create_directories(m_path);
}

ScratchDirectory::~ScratchDirectory() {
  std::error_code ignored;
  std::filesystem::remove_all(m_path, ignored);
}

std::filesystem::path ScratchDirectory::write(const std::string& name,
                                              const std::string& text) const {
  const std::filesystem::path file = m_path / name;
  std::ofstream(file, std::ios::binary) << text;
  return file;
}

std::string boxObj(Vec3 lo, Vec3 hi) {
  const BoxQuads box = boxQuads(lo, hi);
  std::ostringstream out;
  out << "# a box, one quad per face\no box\n";
  for (const Vec3& c : box.corners) out << "v " << c.x << ' ' << c.y << ' ' << c.z << '\n';
  for (const auto& f : box.faces) {
    out << "f " << f[0] + 1 << ' ' << f[1] + 1 << ' ' << f[2] + 1 << ' ' << f[3] + 1 << '\n';
  }
  return out.str();
}

std::string boxStl(Vec3 lo, Vec3 hi) {
  const TriangleMesh mesh = boxMesh(lo, hi);
  std::ostringstream out;
  out << "solid box\n";
  for (const auto& tri : mesh.triangles) {
    const Eigen::Vector3d a = toEigen(mesh.vertices[tri[0]]);
    const Eigen::Vector3d n =
        (toEigen(mesh.vertices[tri[1]]) - a).cross(toEigen(mesh.vertices[tri[2]]) - a).normalized();
    out << "  facet normal " << n.x() << ' ' << n.y() << ' ' << n.z() << "\n    outer loop\n";
    for (std::uint32_t i : tri) {
      const Vec3& v = mesh.vertices[i];
      out << "      vertex " << v.x << ' ' << v.y << ' ' << v.z << '\n';
    }
    out << "    endloop\n  endfacet\n";
  }
  out << "endsolid box\n";
  return out.str();
}

std::string boxPly(Vec3 lo, Vec3 hi) {
  const BoxQuads box = boxQuads(lo, hi);
  std::ostringstream out;
  out << "ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\n"
         "property float z\nelement face 6\nproperty list uchar int vertex_indices\nend_header\n";
  for (const Vec3& c : box.corners) out << c.x << ' ' << c.y << ' ' << c.z << '\n';
  for (const auto& f : box.faces) {
    out << "4 " << f[0] << ' ' << f[1] << ' ' << f[2] << ' ' << f[3] << '\n';
  }
  return out.str();
}

std::string boxGltf(Vec3 lo, Vec3 hi, const std::string& meshes, const std::string& nodes,
                    const std::string& sceneNodes) {
  const TriangleMesh mesh = boxMesh(lo, hi);
  std::vector<std::uint8_t> bytes;
  for (const Vec3& v : mesh.vertices) {
    append(bytes, v.x);
    append(bytes, v.y);
    append(bytes, v.z);
  }
  const std::size_t positionBytes = bytes.size();
  for (const auto& tri : mesh.triangles)
    for (std::uint32_t i : tri) append(bytes, std::uint16_t(i));
  const std::size_t indexBytes = bytes.size() - positionBytes;

  std::ostringstream out;
  out << R"({"asset": {"version": "2.0", "generator": "sandphys mesh tests"},)"
      << R"("buffers": [{"byteLength": )" << bytes.size()
      << R"(, "uri": "data:application/octet-stream;base64,)" << base64(bytes) << R"("}],)"
      << R"("bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": )" << positionBytes
      << R"(, "target": 34962}, {"buffer": 0, "byteOffset": )" << positionBytes
      << R"(, "byteLength": )" << indexBytes << R"(, "target": 34963}],)"
      << R"("accessors": [{"bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3", )"
      << R"("min": [)" << lo.x << ", " << lo.y << ", " << lo.z << R"(], "max": [)" << hi.x << ", "
      << hi.y << ", " << hi.z << R"(]}, )"
      << R"({"bufferView": 1, "componentType": 5123, "count": 36, "type": "SCALAR"}],)"
      << R"("meshes": )"
      << replaceAll(meshes, "PRIMITIVE",
                    R"({"attributes": {"POSITION": 0}, "indices": 1, "mode": 4})")
      << R"(, "nodes": )" << nodes << R"(, "scenes": [{"nodes": )" << sceneNodes
      << R"(}], "scene": 0})" << '\n';
  return out.str();
}

}  // namespace sandphys::mesh_testing
