#include "app/export.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace sandphys::samples {

namespace {

// Nine significant digits: the shortest that reads back into the same float.
void appendFloat(std::string& line, float value) {
  char buffer[32];
  const int length = std::snprintf(buffer, sizeof buffer, "%.9g", static_cast<double>(value));
  line.append(buffer, static_cast<std::size_t>(length));
}

std::vector<const BodyState*> aliveGranules(std::span<const BodyState> bodies) {
  std::vector<const BodyState*> granules;
  granules.reserve(bodies.size());
  for (const BodyState& body : bodies) {
    if (body.alive && body.granule) granules.push_back(&body);
  }
  return granules;
}

}  // namespace

std::optional<ExportFormat> exportFormatFor(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension == ".csv") return ExportFormat::Csv;
  if (extension == ".vtk") return ExportFormat::Vtk;
  return std::nullopt;
}

void writeGranulesCsv(std::ostream& out, std::span<const BodyState> bodies) {
  out << "id,x,y,z,qw,qx,qy,qz,vx,vy,vz\n";
  std::string line;
  for (const BodyState* body : aliveGranules(bodies)) {
    line = std::to_string(body->id.index);
    for (float value : {body->position.x, body->position.y, body->position.z, body->orientation.w,
                        body->orientation.x, body->orientation.y, body->orientation.z,
                        body->velocity.x, body->velocity.y, body->velocity.z}) {
      line += ',';
      appendFloat(line, value);
    }
    line += '\n';
    out << line;
  }
}

void writeGranulesVtk(std::ostream& out, std::span<const BodyState> bodies,
                      std::string_view title) {
  const std::vector<const BodyState*> granules = aliveGranules(bodies);
  const std::size_t n = granules.size();
  // The title is one line of at most 256 characters in the legacy format.
  std::string header(title.substr(0, 255));
  std::replace(header.begin(), header.end(), '\n', ' ');

  out << "# vtk DataFile Version 3.0\n" << header << "\nASCII\nDATASET POLYDATA\n";
  std::string line;
  auto writeRow = [&](std::initializer_list<float> values) {
    line.clear();
    for (float value : values) {
      if (!line.empty()) line += ' ';
      appendFloat(line, value);
    }
    line += '\n';
    out << line;
  };

  out << "POINTS " << n << " float\n";
  for (const BodyState* body : granules) {
    writeRow({body->position.x, body->position.y, body->position.z});
  }
  // Without cells ParaView loads the points but draws nothing; one vertex per point fixes that.
  out << "VERTICES " << n << ' ' << 2 * n << '\n';
  for (std::size_t i = 0; i < n; ++i) out << "1 " << i << '\n';

  out << "POINT_DATA " << n << '\n';
  out << "SCALARS id unsigned_int 1\nLOOKUP_TABLE default\n";
  for (const BodyState* body : granules) out << body->id.index << '\n';
  out << "VECTORS velocity float\n";
  for (const BodyState* body : granules) {
    writeRow({body->velocity.x, body->velocity.y, body->velocity.z});
  }
  // A quaternion is neither a vector nor a tensor in VTK's sense: a 4-component field array.
  out << "FIELD granule_data 1\norientation 4 " << n << " float\n";
  for (const BodyState* body : granules) {
    writeRow({body->orientation.w, body->orientation.x, body->orientation.y, body->orientation.z});
  }
}

void exportGranules(const std::filesystem::path& path, std::span<const BodyState> bodies,
                    std::string_view title) {
  const std::optional<ExportFormat> format = exportFormatFor(path);
  if (!format) {
    throw std::runtime_error("cannot export to '" + path.string() +
                             "': unknown extension (use .csv or .vtk)");
  }
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw std::runtime_error("cannot open '" + path.string() + "' for writing");
  if (*format == ExportFormat::Csv) {
    writeGranulesCsv(out, bodies);
  } else {
    writeGranulesVtk(out, bodies, title);
  }
  out.close();
  if (!out) throw std::runtime_error("error while writing '" + path.string() + "'");
}

}  // namespace sandphys::samples
