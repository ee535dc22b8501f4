// CSV and VTK exports of granules (CPU only, synthetic bodies).
#include <gtest/gtest.h>

#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "app/export.h"

namespace sandphys::samples {
namespace {

std::vector<BodyState> sampleBodies() {
  std::vector<BodyState> bodies;
  BodyState floor{.id = {.index = 0}, .position = {0.0f, 0.0f, 0.0f}};
  floor.granule = false;  // a rough floor is not exported
  bodies.push_back(floor);
  bodies.push_back({.id = {.index = 1},
                    .position = {0.1f, 1.0f / 3.0f, -2.5e-7f},
                    .orientation = {0.5f, -0.5f, 0.5f, 0.5f},
                    .velocity = {1e-9f, -9.81f, 123456.789f}});
  BodyState dead{.id = {.index = 2}, .position = {5.0f, 5.0f, 5.0f}};
  dead.alive = false;  // killed by a sink: not exported
  bodies.push_back(dead);
  bodies.push_back({.id = {.index = 3}, .position = {-0.25f, 0.75f, 0.0f}});
  return bodies;
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> result;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) result.push_back(line);
  return result;
}

std::vector<float> parseFloats(const std::string& line, char separator) {
  std::vector<float> values;
  std::istringstream in(line);
  for (std::string field; std::getline(in, field, separator);) {
    values.push_back(std::stof(field));
  }
  return values;
}

bool sameBits(float a, float b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

TEST(Export, FormatFollowsTheExtension) {
  EXPECT_EQ(exportFormatFor("out/granules.csv"), ExportFormat::Csv);
  EXPECT_EQ(exportFormatFor("granules.CSV"), ExportFormat::Csv);
  EXPECT_EQ(exportFormatFor("granules.vtk"), ExportFormat::Vtk);
  EXPECT_EQ(exportFormatFor("granules.txt"), std::nullopt);
  EXPECT_EQ(exportFormatFor("granules"), std::nullopt);
  EXPECT_EQ(exportFormatFor("csv"), std::nullopt);
}

TEST(Export, CsvHasTheHeaderAndOneExactRowPerAliveGranule) {
  const std::vector<BodyState> bodies = sampleBodies();
  std::ostringstream out;
  writeGranulesCsv(out, bodies);
  const std::vector<std::string> rows = lines(out.str());
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0], "id,x,y,z,qw,qx,qy,qz,vx,vy,vz");
  EXPECT_EQ(rows[1].substr(0, 2), "1,");
  EXPECT_EQ(rows[2].substr(0, 2), "3,");

  // Every value reads back to the same float: no precision lost.
  const std::vector<float> values = parseFloats(rows[1], ',');
  ASSERT_EQ(values.size(), 11u);
  const BodyState& b = bodies[1];
  const float expected[] = {1.0f,
                            b.position.x,
                            b.position.y,
                            b.position.z,
                            b.orientation.w,
                            b.orientation.x,
                            b.orientation.y,
                            b.orientation.z,
                            b.velocity.x,
                            b.velocity.y,
                            b.velocity.z};
  for (std::size_t i = 0; i < values.size(); ++i) {
    EXPECT_TRUE(sameBits(values[i], expected[i])) << "column " << i << ": " << rows[1];
  }
}

TEST(Export, VtkIsLegacyPolydataWithPointsVerticesAndPointData) {
  std::ostringstream out;
  writeGranulesVtk(out, sampleBodies(), "title line\nwith a break");
  const std::vector<std::string> text = lines(out.str());
  ASSERT_GE(text.size(), 4u);
  EXPECT_EQ(text[0], "# vtk DataFile Version 3.0");
  EXPECT_EQ(text[1], "title line with a break");
  EXPECT_EQ(text[2], "ASCII");
  EXPECT_EQ(text[3], "DATASET POLYDATA");
  EXPECT_EQ(text[4], "POINTS 2 float");
  EXPECT_EQ(parseFloats(text[5], ' ').size(), 3u);
  EXPECT_EQ(text[7], "VERTICES 2 4");
  EXPECT_EQ(text[8], "1 0");
  EXPECT_EQ(text[9], "1 1");
  EXPECT_EQ(text[10], "POINT_DATA 2");
  EXPECT_EQ(text[11], "SCALARS id unsigned_int 1");
  EXPECT_EQ(text[12], "LOOKUP_TABLE default");
  EXPECT_EQ(text[13], "1");
  EXPECT_EQ(text[14], "3");
  EXPECT_EQ(text[15], "VECTORS velocity float");
  EXPECT_EQ(text[18], "FIELD granule_data 1");
  EXPECT_EQ(text[19], "orientation 4 2 float");
  const std::vector<float> q = parseFloats(text[20], ' ');
  ASSERT_EQ(q.size(), 4u);
  EXPECT_FLOAT_EQ(q[0], 0.5f);
  EXPECT_FLOAT_EQ(q[1], -0.5f);
  EXPECT_EQ(text.size(), 22u);
}

TEST(Export, UnknownExtensionIsRefused) {
  EXPECT_THROW(exportGranules("granules.txt", sampleBodies(), "t"), std::runtime_error);
}

}  // namespace
}  // namespace sandphys::samples
