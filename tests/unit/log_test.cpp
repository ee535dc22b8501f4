// setLogHandler: sandphys's warnings reach the handler a game installs, and stderr again once it
// is removed.
#include <gtest/gtest.h>
#include <sandphys/sandphys.h>

#include <string>
#include <vector>

namespace sandphys {
namespace {

TEST(Log, WarningsGoToTheInstalledHandlerAndBackToStderr) {
  // An open box (its lid missing) samples with a warning: it bounds no solid.
  TriangleMesh open = boxMesh({0, 0, 0}, {0.1f, 0.1f, 0.1f});
  open.triangles.pop_back();
  open.triangles.pop_back();
  open.source = "lidless box";

  std::vector<std::string> captured;
  setLogHandler([&](LogLevel level, std::string_view message) {
    EXPECT_EQ(level, LogLevel::Warning);
    captured.emplace_back(message);
  });
  ::testing::internal::CaptureStderr();
  const SampledMesh sampled = sampleMesh(open, 0.02f);
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
  ASSERT_EQ(captured.size(), 1u);
  EXPECT_EQ(captured[0], sampled.warnings[0]);
  EXPECT_NE(captured[0].find("lidless box"), std::string::npos) << captured[0];

  setLogHandler({});
  ::testing::internal::CaptureStderr();
  (void)sampleMesh(open, 0.02f);
  const std::string printed = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(printed.rfind("sandphys: warning: mesh 'lidless box'", 0), 0u) << printed;
  EXPECT_EQ(captured.size(), 1u);
}

}  // namespace
}  // namespace sandphys
