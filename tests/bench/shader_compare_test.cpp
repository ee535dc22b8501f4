#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "bench_run.h"
#include "support/test_folder.h"

namespace sandphys::testing {
namespace {

namespace fs = std::filesystem;

// A small box pile, settled into contact, timed for 40 substeps and then run under each version
// (the kernel times are asked for by the test that checks them).
const std::string kPile = smallBoxBench(2000, 40) + " --compare-rounds 2";
const std::string kBench = kPile + " --no-kernel-times --compare-shaders ";

class CompareShaders : public ::testing::Test {
 protected:
  // A copy of the tree's kernels in `name`, with `before` in `file` (under sim/) put as `after`.
  fs::path copyWith(const std::string& name, const std::string& file, const std::string& before,
                    const std::string& after) {
    const fs::path folder = m_folder.path() / name;
    fs::copy(SANDPHYS_SHADER_SOURCE_DIR, folder, fs::copy_options::recursive);
    const fs::path path = folder / "sim" / file;
    std::stringstream text;
    text << std::ifstream(path).rdbuf();
    std::string source = text.str();
    const std::size_t at = source.find(before);
    EXPECT_NE(at, std::string::npos) << before << " not in " << path;
    if (at != std::string::npos) source.replace(at, before.size(), after);
    std::ofstream(path) << source;
    return folder;
  }

  TestFolder m_folder{"sandphys_bench_compare_"};
};

TEST_F(CompareShaders, RunsEachVersionInTurnAndTellsWhichKeepTheFirstsBits) {
  // The tree's kernels are the built-in ones; the third pushes pairs 0.1% harder.
  const fs::path changed =
      copyWith("changed", "contacts.comp", "float xi = params.particleDiameter - dist;",
               "float xi = 1.001 * params.particleDiameter - dist;");
  std::string output;
  const nlohmann::json size =
      benchSize(kBench + SANDPHYS_SHADER_SOURCE_DIR + ",built-in," + changed.string(),
                m_folder.path() / "bench.json", &output);
  const nlohmann::json& versions = size.at("shader_comparison");
  ASSERT_EQ(versions.size(), 3u) << output;
  EXPECT_EQ(versions[0]["folder"], SANDPHYS_SHADER_SOURCE_DIR);
  EXPECT_EQ(versions[1]["folder"], "built-in");
  EXPECT_EQ(versions[2]["folder"], changed.string());
  for (const nlohmann::json& version : versions) {
    // Two rounds of --steps / --compare-rounds substeps each.
    ASSERT_EQ(version["round_ms_per_step"].size(), 2u);
    EXPECT_EQ(version["steps"], 40);
    EXPECT_GT(version["median_ms_per_step"].get<double>(), 0.0);
    EXPECT_LE(version["fastest_ms_per_step"].get<double>(),
              version["median_ms_per_step"].get<double>());
  }
  EXPECT_TRUE(versions[1]["same_state_as_first"]) << output;
  EXPECT_EQ(versions[1]["state_hash"], versions[0]["state_hash"]);
  EXPECT_FALSE(versions[2]["same_state_as_first"]) << output;
  EXPECT_NE(output.find("Kernel versions in one process"), std::string::npos) << output;
  EXPECT_NE(output.find("DIFFER  " + changed.string()), std::string::npos) << output;
}

TEST_F(CompareShaders, EachVersionHasItsKernelTimes) {
  std::string output;
  const nlohmann::json size =
      benchSize(kPile + " --kernel-steps 10 --compare-shaders built-in,built-in",
                m_folder.path() / "bench.json", &output);
  const nlohmann::json& versions = size.at("shader_comparison");
  ASSERT_EQ(versions.size(), 2u) << output;
  for (const nlohmann::json& version : versions) {
    const nlohmann::json& kernels = version.at("kernel_ms_per_substep");
    for (const char* name : {"contacts", "integrate_bodies"}) {
      ASSERT_TRUE(kernels.contains(name)) << output;
      EXPECT_GT(kernels[name].get<double>(), 0.0) << name;
    }
  }
  EXPECT_NE(output.find("Their kernels"), std::string::npos) << output;
}

TEST_F(CompareShaders, AVersionThatDoesNotCompileIsNamedWithItsFileAndLine) {
  const fs::path broken =
      copyWith("broken", "contacts.comp", "void main() {", "float broken = ;\nvoid main() {");
  const ProcessResult result = runCommand(kBench + "built-in," + broken.string());
  EXPECT_EQ(result.exitCode, 1) << result.output;
  EXPECT_NE(result.output.find("--compare-shaders " + broken.string() + ": "), std::string::npos)
      << result.output;
  EXPECT_NE(result.output.find("sim/contacts.comp:"), std::string::npos) << result.output;
}

TEST_F(CompareShaders, AFolderThatIsNotThereIsAUsageError) {
  const std::string missing = (m_folder.path() / "missing").string();
  const ProcessResult result = runCommand(kBench + "built-in," + missing);
  EXPECT_EQ(result.exitCode, 2) << result.output;
  EXPECT_NE(result.output.find("--compare-shaders " + missing + ": not a folder"),
            std::string::npos)
      << result.output;
}

}  // namespace
}  // namespace sandphys::testing
