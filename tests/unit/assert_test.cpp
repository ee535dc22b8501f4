// setAssertHandler: a failed internal check of sandphys reaches the handler with its file, line,
// condition and message; by default it is logged as an error, and the process aborts either way.
#include <gtest/gtest.h>
#include <sandphys/sandphys.h>

#include <cstdio>
#include <string>

#include "core/assert.h"
#include "gl/kernel_profiler.h"

namespace sandphys {
namespace {

// What a test's handler saw; thrown so that the failed call unwinds instead of aborting.
struct Caught {
  std::string file;
  int line = 0;
  std::string condition;
  std::string message;
};

class AssertHandlerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    setAssertHandler([](const AssertFailure& f) {
      throw Caught{std::string(f.file), f.line, std::string(f.condition), std::string(f.message)};
    });
  }
  void TearDown() override { setAssertHandler({}); }
};

TEST_F(AssertHandlerTest, GetsTheFileLineConditionAndMessageOfTheCheck) {
  int evaluated = 0;
  const auto message = [&] {
    ++evaluated;
    return "two is " + std::to_string(2);
  };
  SANDPHYS_ASSERT(1 + 1 == 2, message());
  EXPECT_EQ(evaluated, 0) << "the message of a check that held was built";
  int line = 0;
  try {
    line = __LINE__ + 1;
    SANDPHYS_ASSERT(1 + 1 == 3, message());
    FAIL() << "a false check went on";
  } catch (const Caught& c) {
    EXPECT_EQ(c.file, __FILE__);
    EXPECT_EQ(c.line, line);
    EXPECT_EQ(c.condition, "1 + 1 == 3");
    EXPECT_EQ(c.message, "two is 2");
  }
}

TEST_F(AssertHandlerTest, GetsAnInvariantTheLibraryBreaks) {
  // The World times each dispatch between a begin and an end of its kernel profiler; an end
  // without a begin is a bug of the World, checked before any GL call.
  gl::KernelProfiler profiler;
  profiler.setEnabled(true);
  try {
    profiler.end();
    FAIL() << "an end without a begin went unnoticed";
  } catch (const Caught& c) {
    EXPECT_NE(c.file.find("kernel_profiler.cpp"), std::string::npos) << c.file;
    EXPECT_GT(c.line, 0);
    EXPECT_EQ(c.message, "KernelProfiler::end without a begin (0 dispatches timed)");
  }
}

TEST(AssertDeathTest, TheDefaultLogsTheCheckAsAnErrorAndAborts) {
  EXPECT_DEATH(SANDPHYS_ASSERT(false, "the message"),
               "sandphys: error: .*assert_test\\.cpp:[0-9]+: false: the message");
}

TEST(AssertDeathTest, AHandlerThatReturnsStillAborts) {
  EXPECT_DEATH(
      {
        setAssertHandler(
            [](const AssertFailure& f) { std::fprintf(stderr, "seen line %d\n", f.line); });
        SANDPHYS_ASSERT(false, "returned");
      },
      "seen line [0-9]+");
}

}  // namespace
}  // namespace sandphys
