#pragma once

#include <stdexcept>
#include <string>

namespace sandphys {

/// Every error sandphys throws. The message names the field (or file), the value and the limit,
/// so that a user can fix the input without reading our source.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

/// A setting or descriptor is out of its valid range (NaN, negative, too large, ...).
class InvalidArgument : public Error {
 public:
  using Error::Error;
};

/// A fixed capacity (bodies, particles, colliders) would be exceeded.
class CapacityExceeded : public Error {
 public:
  using Error::Error;
};

/// The OpenGL context is missing, too old, or a GL call or shader failed.
class GpuError : public Error {
 public:
  using Error::Error;
};

/// A mesh file cannot be read, or a mesh (loaded or built in code) cannot make a body: missing
/// file, importer failure, no triangles, non-finite vertices, indices out of range, no area, or an
/// open mesh where a closed one is required. The message names the file (TriangleMesh::source).
class MeshError : public Error {
 public:
  using Error::Error;
};

/// A recording cannot be read or replayed: missing, not a recording, another format version,
/// truncated, damaged (bad checksum) or malformed. The message names the file.
class RecordingError : public Error {
 public:
  using Error::Error;
};

/// A stale or invalid id was passed to the world.
class InvalidId : public Error {
 public:
  using Error::Error;
};

}  // namespace sandphys
