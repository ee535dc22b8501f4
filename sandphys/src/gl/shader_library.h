#pragma once

#include <GL/glew.h>

#include <span>
#include <string>
#include <vector>

#include "gl/embedded_shaders.h"

namespace sandphys::gl {

/// A GLSL source after #include expansion: `#line L F` directives name each original file by its
/// index F in `files`, so that compiler messages can be mapped back to file and line.
struct ExpandedSource {
  std::string text;
  std::vector<std::string> files;
};

/// One stage of a graphics program: GL_VERTEX_SHADER, GL_FRAGMENT_SHADER, ... and its file.
struct ShaderStage {
  GLenum type;
  std::string name;
};

/// A shader file made at run time, from C++ (e.g. declarations generated from a table).
struct GeneratedShader {
  std::string name;  ///< path relative to shaders/, as an #include names it
  std::string source;
};

/// Finds shader files (generated; embedded at build time; or, when SANDPHYS_SHADER_DIR is set in
/// the environment, read from that directory so that a viewer can hot-reload them), expands
/// `#include "relative/path.glsl"` once per file, and compiles programs.
class ShaderLibrary {
 public:
  /// The library's own shaders (shaders/sim), with the buffer declarations generated from
  /// core/gpu_buffers.def.
  ShaderLibrary();
  /// Another set embedded with sandphys_embed_shaders(... FUNCTION f) (e.g. the renderer's), and
  /// files generated at run time, which take precedence over files of the same name.
  explicit ShaderLibrary(std::span<const EmbeddedShader> embedded,
                         std::vector<GeneratedShader> generated = {});

  /// Source of one file relative to shaders/; throws GpuError if there is none.
  std::string source(const std::string& name) const;
  /// `name` with includes expanded and `defines` ("NAME VALUE" each) inserted after #version.
  ExpandedSource expand(const std::string& name, const std::vector<std::string>& defines) const;
  /// Compiles and links a compute program. Throws GpuError whose message names the original
  /// file and line of each compiler error.
  GLuint compileCompute(const std::string& name,
                        const std::vector<std::string>& defines = {}) const;
  /// Compiles every stage (each expanded with `defines`) and links them into one program; errors
  /// as compileCompute's.
  GLuint compileProgram(const std::vector<ShaderStage>& stages,
                        const std::vector<std::string>& defines = {}) const;

  /// Rewrites "F:L(C): msg" driver messages with file names; exposed for tests.
  static std::string mapLog(const std::string& log, const std::vector<std::string>& files);

 private:
  std::string m_directory;  // empty: embedded sources
  std::span<const EmbeddedShader> m_embedded;
  std::vector<GeneratedShader> m_generated;
};

}  // namespace sandphys::gl
