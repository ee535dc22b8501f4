#include "gl/shader_library.h"

#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>
#include <unordered_set>
#include <utility>

#include "core/gpu_buffers.h"
#include "gl/embedded_shaders.h"
#include "sandphys/error.h"

namespace sandphys::gl {
namespace {

// Every file gets its own range of line numbers in the expanded source, so that a message can be
// traced to its file from the line number alone: Mesa reports the right line but, for some
// errors, source string 0 instead of the number given by #line.
constexpr int kLinesPerFile = 100000;

std::string lineDirective(int line, int fileIndex) {
  return "#line " + std::to_string(fileIndex * kLinesPerFile + line) + " " +
         std::to_string(fileIndex) + "\n";
}

std::string directoryOf(const std::string& name) {
  auto slash = name.rfind('/');
  return slash == std::string::npos ? std::string() : name.substr(0, slash + 1);
}

// Collapses "a/b/../c" so that one file reached by two relative paths is included once.
std::string normalisePath(const std::string& path) {
  std::vector<std::string> parts;
  std::stringstream in(path);
  std::string part;
  while (std::getline(in, part, '/')) {
    if (part.empty() || part == ".") continue;
    if (part == ".." && !parts.empty()) {
      parts.pop_back();
    } else {
      parts.push_back(part);
    }
  }
  std::string out;
  for (const auto& p : parts) out += (out.empty() ? "" : "/") + p;
  return out;
}

struct Expander {
  const ShaderLibrary& library;
  ExpandedSource result;
  std::unordered_set<std::string> included;

  void append(const std::string& name, const std::vector<std::string>* defines) {
    const int fileIndex = static_cast<int>(result.files.size());
    result.files.push_back(name);
    included.insert(name);
    std::istringstream lines(library.source(name));
    std::string line;
    int lineNumber = 0;
    static const std::regex includeRe(R"(^\s*#\s*include\s+\"([^\"]+)\"\s*$)");
    static const std::regex versionRe(R"(^\s*#\s*version\b.*)");
    while (std::getline(lines, line)) {
      ++lineNumber;
      std::smatch match;
      if (defines && std::regex_match(line, versionRe)) {
        result.text += line + "\n";
        for (const auto& define : *defines) result.text += "#define " + define + "\n";
        result.text += lineDirective(lineNumber + 1, fileIndex);
        continue;
      }
      if (std::regex_match(line, match, includeRe)) {
        std::string child = normalisePath(directoryOf(name) + match[1].str());
        if (!included.count(child)) {
          result.text += lineDirective(1, int(result.files.size()));
          append(child, nullptr);
        }
        result.text += lineDirective(lineNumber + 1, fileIndex);
        continue;
      }
      result.text += line + "\n";
    }
  }
};

}  // namespace

ShaderLibrary::ShaderLibrary()
    : ShaderLibrary(embeddedShaders(),
                    {{detail::kBufferDeclarationsFile, detail::generatedBufferDeclarations()}}) {}

ShaderLibrary::ShaderLibrary(std::span<const EmbeddedShader> embedded,
                             std::vector<GeneratedShader> generated)
    : m_embedded(embedded), m_generated(std::move(generated)) {
  if (const char* dir = std::getenv("SANDPHYS_SHADER_DIR"); dir && *dir) m_directory = dir;
}

std::string ShaderLibrary::source(const std::string& name) const {
  for (const auto& shader : m_generated) {
    if (name == shader.name) return shader.source;
  }
  if (!m_directory.empty()) {
    std::ifstream file(m_directory + "/" + name);
    if (!file) {
      throw GpuError("shader file '" + m_directory + "/" + name +
                     "' not found (SANDPHYS_SHADER_DIR is set)");
    }
    std::stringstream text;
    text << file.rdbuf();
    return text.str();
  }
  for (const auto& shader : m_embedded) {
    if (name == shader.name) return shader.source;
  }
  throw GpuError("shader file '" + name + "' is not among the embedded shaders (shaders/)");
}

ExpandedSource ShaderLibrary::expand(const std::string& name,
                                     const std::vector<std::string>& defines) const {
  Expander expander{*this, {}, {}};
  expander.append(name, &defines);
  return std::move(expander.result);
}

std::string ShaderLibrary::mapLog(const std::string& log, const std::vector<std::string>& files) {
  // Mesa writes "0:12(5): error: ...", NVIDIA "0(12) : error ...": both start with file index.
  static const std::regex mesaRe(R"(^(\d+):(\d+)\((\d+)\)(.*)$)");
  static const std::regex nvRe(R"(^(\d+)\((\d+)\)(.*)$)");
  std::istringstream lines(log);
  std::string line;
  std::string out;
  while (std::getline(lines, line)) {
    std::smatch m;
    // The file comes from the line number's range (see kLinesPerFile); the source number is a
    // fallback for lines below the first range.
    auto location = [&](const std::string& source, const std::string& lineText) {
      long long index = std::stoll(source);
      long long number = std::stoll(lineText);
      if (number >= kLinesPerFile) {
        index = number / kLinesPerFile;
        number %= kLinesPerFile;
      }
      std::string name = index >= 0 && std::size_t(index) < files.size()
                             ? files[std::size_t(index)]
                             : "<file " + std::to_string(index) + ">";
      return "shaders/" + name + ":" + std::to_string(number);
    };
    if (std::regex_match(line, m, mesaRe)) {
      out += location(m[1], m[2]) + ":" + m[3].str() + m[4].str();
    } else if (std::regex_match(line, m, nvRe)) {
      out += location(m[1], m[2]) + ":" + m[3].str();
    } else {
      out += line;
    }
    out += "\n";
  }
  return out;
}

GLuint ShaderLibrary::compileCompute(const std::string& name,
                                     const std::vector<std::string>& defines) const {
  return compileProgram({{GL_COMPUTE_SHADER, name}}, defines);
}

GLuint ShaderLibrary::compileProgram(const std::vector<ShaderStage>& stages,
                                     const std::vector<std::string>& defines) const {
  std::vector<GLuint> shaders;
  std::vector<std::string> files;  // every stage's files, for the link log
  std::string names;
  auto release = [&] {
    for (GLuint shader : shaders) glDeleteShader(shader);
  };
  for (const ShaderStage& stage : stages) {
    ExpandedSource expanded = expand(stage.name, defines);
    names += (names.empty() ? "shaders/" : " + shaders/") + stage.name;
    GLuint shader = glCreateShader(stage.type);
    shaders.push_back(shader);
    const char* text = expanded.text.c_str();
    glShaderSource(shader, 1, &text, nullptr);
    glCompileShader(shader);
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
      GLint length = 0;
      glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
      std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
      glGetShaderInfoLog(shader, length, nullptr, log.data());
      release();
      throw GpuError("shader 'shaders/" + stage.name + "' failed to compile:\n" +
                     mapLog(log.c_str(), expanded.files));
    }
    if (files.empty()) files = expanded.files;
  }
  GLuint program = glCreateProgram();
  for (GLuint shader : shaders) glAttachShader(program, shader);
  glLinkProgram(program);
  release();
  GLint ok = GL_FALSE;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    GLint length = 0;
    glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
    glGetProgramInfoLog(program, length, nullptr, log.data());
    glDeleteProgram(program);
    throw GpuError("shader '" + names + "' failed to link:\n" + mapLog(log.c_str(), files));
  }
  return program;
}

}  // namespace sandphys::gl
