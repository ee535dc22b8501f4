#include "gl/shader_library.h"

#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>
#include <unordered_set>

#include "gl/embedded_shaders.h"
#include "sandphys/error.h"

namespace sandphys::gl {
namespace {

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
        result.text += "#line " + std::to_string(lineNumber + 1) + " " + std::to_string(fileIndex) + "\n";
        continue;
      }
      if (std::regex_match(line, match, includeRe)) {
        std::string child = normalisePath(directoryOf(name) + match[1].str());
        if (!included.count(child)) {
          result.text += "#line 1 " + std::to_string(result.files.size()) + "\n";
          append(child, nullptr);
        }
        result.text += "#line " + std::to_string(lineNumber + 1) + " " + std::to_string(fileIndex) + "\n";
        continue;
      }
      result.text += line + "\n";
    }
  }
};

}  // namespace

ShaderLibrary::ShaderLibrary() {
  if (const char* dir = std::getenv("SANDPHYS_SHADER_DIR"); dir && *dir) m_directory = dir;
}

std::string ShaderLibrary::source(const std::string& name) const {
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
  for (const auto& shader : embeddedShaders()) {
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
    auto fileName = [&](const std::string& index) {
      std::size_t i = std::stoul(index);
      return i < files.size() ? files[i] : "<file " + index + ">";
    };
    if (std::regex_match(line, m, mesaRe)) {
      out += "shaders/" + fileName(m[1]) + ":" + m[2].str() + ":" + m[3].str() + m[4].str();
    } else if (std::regex_match(line, m, nvRe)) {
      out += "shaders/" + fileName(m[1]) + ":" + m[2].str() + ":" + m[3].str();
    } else {
      out += line;
    }
    out += "\n";
  }
  return out;
}

GLuint ShaderLibrary::compileCompute(const std::string& name,
                                     const std::vector<std::string>& defines) const {
  ExpandedSource expanded = expand(name, defines);
  GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
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
    glDeleteShader(shader);
    throw GpuError("shader 'shaders/" + name + "' failed to compile:\n" +
                   mapLog(log.c_str(), expanded.files));
  }
  GLuint program = glCreateProgram();
  glAttachShader(program, shader);
  glLinkProgram(program);
  glDeleteShader(shader);
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    GLint length = 0;
    glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
    glGetProgramInfoLog(program, length, nullptr, log.data());
    glDeleteProgram(program);
    throw GpuError("shader 'shaders/" + name + "' failed to link:\n" +
                   mapLog(log.c_str(), expanded.files));
  }
  return program;
}

}  // namespace sandphys::gl
