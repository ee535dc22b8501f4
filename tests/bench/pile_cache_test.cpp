#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench_run.h"
#include "support/test_folder.h"

namespace sandphys::testing {
namespace {

namespace fs = std::filesystem;

// A small box pile, briefly settled: what the cache keeps does not depend on how settled it is.
const std::string kBench = smallBoxBench(4000, 100) + " --kernel-steps 10";

class PileCache : public ::testing::Test {
 protected:
  // One run with the cache; its JSON's only size.
  nlohmann::json run(const std::string& name, const std::string& extra = "",
                     std::string* output = nullptr) {
    return benchSize(kBench + extra + " --pile-cache " + (m_dir / "piles").string(),
                     m_dir / (name + ".json"), output);
  }

  std::vector<fs::path> piles() const {
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(m_dir / "piles")) files.push_back(entry.path());
    return files;
  }

  TestFolder m_folder{"sandphys_pile_cache_"};
  const fs::path& m_dir = m_folder.path();
};

TEST_F(PileCache, ASecondRunRestoresThePileAndMeasuresWhatTheFirstDid) {
  const nlohmann::json first = run("first");
  ASSERT_EQ(piles().size(), 1u);
  EXPECT_EQ(first["settle"]["restored_from"], "");
  std::string output;
  const nlohmann::json second = run("second", "", &output);
  EXPECT_EQ(second["settle"]["restored_from"], piles().front().string()) << output;
  EXPECT_NE(output.find("restored from"), std::string::npos) << output;
  EXPECT_EQ(second["settle"]["steps"], first["settle"]["steps"]);
  // Every figure of the pile's state, at the start of timing and at its end, to the last bit.
  EXPECT_EQ(second["state"]["settled"], first["state"]["settled"]);
  EXPECT_EQ(second["state"]["measured"], first["state"]["measured"]);
  EXPECT_GT(first["state"]["measured"]["contacts"].get<int>(), 100);
  ASSERT_EQ(piles().size(), 1u);
}

TEST_F(PileCache, AnotherSeedSettlesAndKeepsAPileOfItsOwn) {
  const nlohmann::json one = run("one");
  const nlohmann::json other = run("other", " --seed 2");
  EXPECT_EQ(other["settle"]["restored_from"], "");
  EXPECT_EQ(piles().size(), 2u);
  EXPECT_NE(other["state"]["settled"], one["state"]["settled"]);
}

TEST_F(PileCache, ADamagedFileIsNamedAndPassedOver) {
  run("first");
  ASSERT_EQ(piles().size(), 1u);
  const fs::path file = piles().front();
  fs::resize_file(file, fs::file_size(file) / 2);
  std::string output;
  const nlohmann::json again = run("again", "", &output);
  EXPECT_EQ(again["settle"]["restored_from"], "");
  EXPECT_NE(output.find("cannot use the settled pile " + file.string()), std::string::npos)
      << output;
}

}  // namespace
}  // namespace sandphys::testing
