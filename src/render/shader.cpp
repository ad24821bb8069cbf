#include "render/shader.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>

namespace rtsph::render {

std::string shader_source(std::string_view name) {
  if (const char* dir = std::getenv("RTSPH_SHADER_DIR"); dir && *dir) {
    std::ifstream in(fmt::format("{}/{}", dir, name));
    if (in) {
      std::stringstream ss;
      ss << in.rdbuf();
      return ss.str();
    }
  }
  for (int i = 0; i < kEmbeddedShaderCount; ++i)
    if (name == kEmbeddedShaders[i].name) return kEmbeddedShaders[i].source;
  throw std::runtime_error(fmt::format("unknown shader '{}'", name));
}

std::vector<std::string> shader_names() {
  std::vector<std::string> out;
  for (int i = 0; i < kEmbeddedShaderCount; ++i) out.emplace_back(kEmbeddedShaders[i].name);
  return out;
}

GLenum shader_stage(std::string_view name) {
  auto ends = [&](std::string_view s) {
    return name.size() >= s.size() && name.substr(name.size() - s.size()) == s;
  };
  if (ends(".vert")) return GL_VERTEX_SHADER;
  if (ends(".frag")) return GL_FRAGMENT_SHADER;
  if (ends(".comp")) return GL_COMPUTE_SHADER;
  if (ends(".geom")) return GL_GEOMETRY_SHADER;
  throw std::runtime_error(fmt::format("shader '{}': unknown stage extension", name));
}

GLuint compile_shader(GLenum stage, std::string_view name, const std::string& source) {
  GLuint s = glCreateShader(stage);
  const char* src = source.c_str();
  glShaderSource(s, 1, &src, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    GLint len = 0;
    glGetShaderiv(s, GL_INFO_LOG_LENGTH, &len);
    std::string log(static_cast<std::size_t>(std::max(len, 1)), '\0');
    glGetShaderInfoLog(s, len, nullptr, log.data());
    glDeleteShader(s);
    throw std::runtime_error(fmt::format("shader {} failed to compile: {}", name, log.c_str()));
  }
  return s;
}

Program::Program(const std::vector<std::string>& stage_files) {
  std::vector<GLuint> shaders;
  try {
    for (const auto& f : stage_files)
      shaders.push_back(compile_shader(shader_stage(f), f, shader_source(f)));
  } catch (...) {
    for (GLuint s : shaders) glDeleteShader(s);
    throw;
  }
  id_ = glCreateProgram();
  for (GLuint s : shaders) glAttachShader(id_, s);
  glLinkProgram(id_);
  for (GLuint s : shaders) {
    glDetachShader(id_, s);
    glDeleteShader(s);
  }
  GLint ok = 0;
  glGetProgramiv(id_, GL_LINK_STATUS, &ok);
  if (!ok) {
    GLint len = 0;
    glGetProgramiv(id_, GL_INFO_LOG_LENGTH, &len);
    std::string log(static_cast<std::size_t>(std::max(len, 1)), '\0');
    glGetProgramInfoLog(id_, len, nullptr, log.data());
    glDeleteProgram(id_);
    id_ = 0;
    std::string names;
    for (const auto& f : stage_files) names += (names.empty() ? "" : "+") + f;
    throw std::runtime_error(fmt::format("program {} failed to link: {}", names, log.c_str()));
  }
}

Program::~Program() {
  if (id_) glDeleteProgram(id_);
}

Program& Program::operator=(Program&& o) noexcept {
  if (this != &o) {
    if (id_) glDeleteProgram(id_);
    id_ = o.id_;
    o.id_ = 0;
  }
  return *this;
}

}  // namespace rtsph::render
