// The shader loader without a GL context: #include expansion with #line, and log mapping.
#include <gtest/gtest.h>

#include <algorithm>

#include "gl/shader_library.h"

namespace sandphys::gl {
namespace {

TEST(ShaderLibrary, ExpandsIncludesOnceAndMarksEveryFileWithLineDirectives) {
  ShaderLibrary library;
  ExpandedSource source = library.expand("sim/contacts.comp", {"CONTACT_LIST 1"});
  ASSERT_GE(source.files.size(), 4u);
  EXPECT_EQ(source.files[0], "sim/contacts.comp");
  EXPECT_EQ(source.files[1], "sim/common/layout.glsl");
  EXPECT_EQ(source.text.rfind("#version 450", 0), 0u) << "version must stay first";
  EXPECT_NE(source.text.find("#define CONTACT_LIST 1"), std::string::npos);
  EXPECT_EQ(source.text.find("#include"), std::string::npos);
  EXPECT_NE(source.text.find("#line 100001 1\n"), std::string::npos);
  // layout.glsl is included by contacts.comp only once although other headers need it too.
  std::size_t count = 0;
  for (const auto& f : source.files) count += f == "sim/common/layout.glsl";
  EXPECT_EQ(count, 1u);
}

TEST(ShaderLibrary, ServesTheBufferDeclarationsGeneratedFromTheTable) {
  ShaderLibrary library;
  ExpandedSource source = library.expand("sim/grid_count.comp", {});
  EXPECT_NE(std::find(source.files.begin(), source.files.end(), "sim/common/buffers.glsl"),
            source.files.end());
  EXPECT_NE(source.text.find("#define BODY_POSITION(access) layout(std430, binding = 0) access "
                             "buffer BodyPositionBuffer { vec4 bodyPosition[]; };"),
            std::string::npos);
  EXPECT_NE(source.text.find("#define CELL_START_TEXTURE layout(binding = "), std::string::npos);
}

TEST(ShaderLibrary, AGeneratedFileTakesPrecedence) {
  ShaderLibrary library(embeddedShaders(), {{"sim/common/layout.glsl", "// replaced\n"}});
  EXPECT_EQ(library.source("sim/common/layout.glsl"), "// replaced\n");
  EXPECT_NE(library.source("sim/contacts.comp").find("#version"), std::string::npos);
}

TEST(ShaderLibrary, MapsDriverMessagesToFileAndLine) {
  // The file is known from the line range even when the driver reports source string 0.
  std::string mapped = ShaderLibrary::mapLog("0:100042(7): error: `foo' undeclared\nplain line\n",
                                             {"sim/a.comp", "sim/common/b.glsl"});
  EXPECT_NE(mapped.find("shaders/sim/common/b.glsl:42:7: error: `foo' undeclared"),
            std::string::npos)
      << mapped;
  EXPECT_NE(ShaderLibrary::mapLog("0:12(3): x", {"sim/a.comp"}).find("shaders/sim/a.comp:12:3: x"),
            std::string::npos);
  EXPECT_NE(mapped.find("plain line"), std::string::npos);
}

TEST(ShaderLibrary, UnknownFileIsAnError) {
  ShaderLibrary library;
  EXPECT_THROW(library.source("sim/does_not_exist.comp"), std::exception);
}

}  // namespace
}  // namespace sandphys::gl
