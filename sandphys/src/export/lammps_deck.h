#pragma once

// The text of the LAMMPS input deck for a World (lammps_export.cpp writes it with the data files).

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "export/lammps_scene.h"
#include "sandphys/lammps_export.h"

namespace sandphys::detail {

struct LammpsDeck {
  std::string text;
  std::array<Vec3d, 2> box{};  // the data file's box: lo and hi corners, m
  std::uint32_t walls = 0;
  std::uint32_t sinks = 0;
  std::vector<std::string> notMapped;
};

LammpsDeck composeLammpsDeck(const World& world, const LammpsScene& scene,
                             const LammpsExportOptions& options);

}  // namespace sandphys::detail
