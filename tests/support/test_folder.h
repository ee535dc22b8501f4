#pragma once

// A fresh folder for the running test, removed when it ends.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace sandphys::testing {

/// TEMP/<prefix><test name>, emptied on construction and removed on destruction.
class TestFolder {
 public:
  explicit TestFolder(const std::string& prefix)
      : m_path(std::filesystem::temp_directory_path() /
               (prefix + ::testing::UnitTest::GetInstance()->current_test_info()->name())) {
    std::filesystem::remove_all(m_path);
    std::filesystem::create_directories(m_path);
  }
  ~TestFolder() { std::filesystem::remove_all(m_path); }
  TestFolder(const TestFolder&) = delete;
  TestFolder& operator=(const TestFolder&) = delete;

  const std::filesystem::path& path() const { return m_path; }

 private:
  std::filesystem::path m_path;
};

}  // namespace sandphys::testing
