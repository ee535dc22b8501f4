// A shader that fails to compile is reported with the original file and line, after #include
// expansion; a World whose kernels fail to compile throws GpuError before doing anything.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "gl/shader_library.h"
#include "support/test_world.h"

namespace sandphys {
namespace {

namespace fs = std::filesystem;

// Points the shader loader at `dir` for the lifetime of the object.
class ShaderDirectory {
 public:
  explicit ShaderDirectory(const fs::path& dir) { setenv("SANDPHYS_SHADER_DIR", dir.c_str(), 1); }
  ~ShaderDirectory() { unsetenv("SANDPHYS_SHADER_DIR"); }
};

fs::path freshDirectory(const char* name) {
  fs::path dir = fs::temp_directory_path() / (std::string(name) + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "sim" / "common");
  return dir;
}

void write(const fs::path& file, const std::string& text) {
  std::ofstream out(file);
  out << text;
}

TEST(ShaderErrors, NameTheIncludedFileAndLine) {
  testing::gpu().makeCurrent();
  fs::path dir = freshDirectory("sandphys_bad_shader");
  write(dir / "sim" / "bad.comp",
        "#version 450\n#include \"common/helper.glsl\"\nlayout(local_size_x = 1) in;\nvoid main() "
        "{ helper(); }\n");
  write(dir / "sim" / "common" / "helper.glsl",
        "// helper\n\nvoid helper() { undefinedThing = 1.0; }\n");
  ShaderDirectory use(dir);
  gl::ShaderLibrary library;
  try {
    library.compileCompute("sim/bad.comp");
    FAIL() << "a broken shader compiled";
  } catch (const GpuError& e) {
    std::string message = e.what();
    EXPECT_NE(message.find("shaders/sim/common/helper.glsl:3:"), std::string::npos) << message;
    EXPECT_NE(message.find("undefinedThing"), std::string::npos) << message;
  }
  fs::remove_all(dir);
}

TEST(ShaderErrors, StopAWorldFromBeingCreated) {
  testing::gpu().makeCurrent();
  fs::path dir = freshDirectory("sandphys_bad_kernels");
  fs::remove_all(dir);
  fs::copy(SANDPHYS_SHADER_SOURCE_DIR, dir, fs::copy_options::recursive);
  // Break the contact law on its first line.
  fs::path law = dir / "sim" / "common" / "contact_law.glsl";
  std::stringstream original;
  original << std::ifstream(law).rdbuf();
  write(law, "float broken = ;\n" + original.str());
  ShaderDirectory use(dir);
  try {
    World world(testing::gpu(), testing::smallSettings());
    FAIL() << "a world was created from broken kernels";
  } catch (const GpuError& e) {
    std::string message = e.what();
    EXPECT_NE(message.find("shaders/sim/common/contact_law.glsl:1:"), std::string::npos) << message;
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace sandphys
