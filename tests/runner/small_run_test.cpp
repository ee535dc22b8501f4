// Checks the files written by the CTest fixture runner.small_run (tests/runner/CMakeLists.txt):
//   sandphys-samples --headless --scene cylinder-pile --batch 8 4 8 --param radius=15
//                    --param first-drop=2 --frames 12 --metrics metrics.json
//                    --export granules.csv --export granules.vtk
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scenes/scene.h"

namespace sandphys::testing {
namespace {

const std::string kDir = SANDPHYS_SMALL_RUN_DIR;
constexpr unsigned kGranules = 8 * 4 * 8;
constexpr float kRadius = 15.0f * 0.02f;  // m, as the scene computes it
constexpr int kFrames = 12;

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  EXPECT_TRUE(in) << "missing " << path << " (run the fixture runner.small_run)";
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

nlohmann::json metrics() {
  return nlohmann::json::parse(readFile(kDir + "/metrics.json"));
}

TEST(SmallRun, MetricsHaveEveryField) {
  const nlohmann::json m = metrics();
  for (const char* key : {"scene",
                          "granules",
                          "particles",
                          "body_slots",
                          "bodies",
                          "bodies_series",
                          "frame_series",
                          "steps",
                          "simulated_seconds",
                          "wall_seconds",
                          "cundall_number",
                          "seconds_simulated_per_wall_second",
                          "contacts",
                          "kinetic_energy",
                          "max_overlap_d",
                          "penetration_clamps",
                          "velocity_clamps",
                          "granules_spawned",
                          "granules_killed",
                          "granules_not_born",
                          "contact_slot_overflows",
                          "granules_lost",
                          "time_step",
                          "gpu",
                          "scene_parameters",
                          "scene_metrics"}) {
    EXPECT_TRUE(m.contains(key)) << key;
  }
}

TEST(SmallRun, MetricsDescribeTheRun) {
  const nlohmann::json m = metrics();
  EXPECT_EQ(m["scene"], "cylinder-pile");
  EXPECT_EQ(m["granules"], kGranules);
  EXPECT_EQ(m["granules_spawned"], kGranules);
  EXPECT_EQ(m["granules_killed"], 0);
  EXPECT_EQ(m["granules_not_born"], 0);       // a batch is placed, not emitted
  EXPECT_EQ(m["body_slots"], kGranules + 1);  // + the rough floor
  // The cylinder pile has no bodies but sand.
  EXPECT_EQ(m["bodies"], nlohmann::json::array());
  EXPECT_EQ(m["bodies_series"], nlohmann::json::array());
  EXPECT_EQ(m["particles"],
            4 * kGranules + roughFloorParticles(RoughFloor{.radius = kRadius}, 0.02f));
  EXPECT_EQ(m["scene_parameters"]["batch"], nlohmann::json::array({8, 4, 8}));
  EXPECT_FALSE(m["gpu"].get<std::string>().empty());

  // Time: kFrames frames of 1/60 s in whole substeps of time_step.
  const double dt = m["time_step"];
  const double steps = m["steps"];
  const double simulated = m["simulated_seconds"];
  EXPECT_GT(dt, 0.0);
  EXPECT_GT(steps, 0.0);
  EXPECT_NEAR(simulated, steps * dt, 1e-6 * simulated + 1e-9);
  EXPECT_NEAR(simulated + m["dropped_seconds"].get<double>(), kFrames / 60.0, dt + 1e-6);

  EXPECT_GT(m["wall_seconds"].get<double>(), 0.0);
  EXPECT_GT(m["cundall_number"].get<double>(), 0.0);
  // One sample per frame (the app reads statistics every frame), ending at the run's end, with
  // every granule alive and, without sleep, none asleep.
  const nlohmann::json& frames = m["frame_series"];
  ASSERT_EQ(frames.size(), std::size_t(kFrames));
  EXPECT_NEAR(frames.back()[0].get<double>(), simulated, 1e-9);
  EXPECT_GT(frames.back()[1].get<double>(), 0.0);
  EXPECT_EQ(frames.back()[2], kGranules);
  EXPECT_EQ(frames.back()[3], 0);
  EXPECT_GT(m["seconds_simulated_per_wall_second"].get<double>(), 0.0);
}

TEST(SmallRun, GranulesLandedInsideTheCylinderWithoutDeepOverlap) {
  const nlohmann::json m = metrics();
  // The batch starts 2 d above the floor and has fallen onto it after 0.2 s.
  EXPECT_GT(m["contacts"].get<double>(), kGranules) << "granules should rest on the floor";
  // Granules resting on the floor and on each other press in: some overlap, and not deep.
  EXPECT_GT(m["max_overlap_d"].get<double>(), 0.0);
  EXPECT_LT(m["max_overlap_d"].get<double>(), 0.1);  // the paper's guard is d/10
  EXPECT_EQ(m["granules_lost"], 0);
  const double energy = m["kinetic_energy"];
  EXPECT_TRUE(std::isfinite(energy));
  EXPECT_GE(energy, 0.0);
  EXPECT_EQ(m["scene_metrics"]["batches_dropped"], 1.0);
  EXPECT_LT(m["scene_metrics"]["pile_top_d"].get<double>(), 12.0);  // 4 layers, fallen
}

TEST(SmallRun, CsvHasTheHeaderAndOneRowPerGranule) {
  std::istringstream csv(readFile(kDir + "/granules.csv"));
  std::string line;
  ASSERT_TRUE(std::getline(csv, line));
  EXPECT_EQ(line, "id,x,y,z,qw,qx,qy,qz,vx,vy,vz");
  std::set<unsigned long> ids;
  unsigned rows = 0;
  while (std::getline(csv, line)) {
    ++rows;
    std::vector<double> values;
    std::istringstream fields(line);
    for (std::string field; std::getline(fields, field, ',');) values.push_back(std::stod(field));
    ASSERT_EQ(values.size(), 11u) << line;
    EXPECT_TRUE(ids.insert(static_cast<unsigned long>(values[0])).second) << "duplicate id";
    const double x = values[1], y = values[2], z = values[3];
    EXPECT_LE(std::hypot(x, z), kRadius) << line;
    EXPECT_GT(y, 0.0) << line;
    const double qNorm = std::sqrt(values[4] * values[4] + values[5] * values[5] +
                                   values[6] * values[6] + values[7] * values[7]);
    EXPECT_NEAR(qNorm, 1.0, 1e-4) << line;
  }
  EXPECT_EQ(rows, metrics()["granules"].get<unsigned>());
  EXPECT_EQ(rows, kGranules);
}

TEST(SmallRun, VtkIsLegacyPolydataOfEveryGranule) {
  const std::string vtk = readFile(kDir + "/granules.vtk");
  EXPECT_EQ(vtk.rfind("# vtk DataFile Version", 0), 0u);
  EXPECT_NE(vtk.find("\nDATASET POLYDATA\n"), std::string::npos);
  EXPECT_NE(vtk.find("\nPOINTS 256 float\n"), std::string::npos);
  EXPECT_NE(vtk.find("\nPOINT_DATA 256\n"), std::string::npos);
  EXPECT_NE(vtk.find("\norientation 4 256 float\n"), std::string::npos);
}

}  // namespace
}  // namespace sandphys::testing
