#pragma once

#include <filesystem>
#include <optional>
#include <ostream>
#include <span>
#include <string_view>

#include <sandphys/readback.h>

namespace sandphys::samples {

/// File formats of --export, chosen by the file's extension.
enum class ExportFormat {
  Csv,  ///< ".csv": header id,x,y,z,qw,qx,qy,qz,vx,vy,vz; one row per alive granule
  Vtk,  ///< ".vtk": legacy VTK POLYDATA, ASCII (ParaView, VisIt)
};

/// The format for `path`'s extension (case-insensitive), or nothing for an unknown one.
std::optional<ExportFormat> exportFormatFor(const std::filesystem::path& path);

/// Writes the alive granules of `bodies` as CSV: the header `id,x,y,z,qw,qx,qy,qz,vx,vy,vz`, then
/// one row per granule (id = body slot; position m, orientation, velocity m/s; SI, y up) with
/// every float printed to full precision (%.9g), so that the values read back bit for bit.
void writeGranulesCsv(std::ostream& out, std::span<const BodyState> bodies);

/// Writes the alive granules of `bodies` as legacy VTK POLYDATA (version 3.0, ASCII): points at
/// the granule centres, one vertex cell per point so that they render, and point data "id",
/// "velocity" (vector) and "orientation" (4 components w, x, y, z). `title` becomes the header
/// line (at most 255 characters are kept).
void writeGranulesVtk(std::ostream& out, std::span<const BodyState> bodies, std::string_view title);

/// Writes `bodies` to `path` in the format of its extension. Throws std::runtime_error naming the
/// path when the extension is unknown or the file cannot be written.
void exportGranules(const std::filesystem::path& path, std::span<const BodyState> bodies,
                    std::string_view title);

}  // namespace sandphys::samples
