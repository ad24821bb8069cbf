#pragma once
// GLSL programs. Sources are embedded into the binary at build time (shaders/embed.cmake);
// setting RTSPH_SHADER_DIR in the environment loads them from that folder instead, for
// editing shaders without rebuilding.
#include <epoxy/gl.h>

#include <string>
#include <string_view>
#include <vector>

namespace rtsph::render {

struct EmbeddedShader {
  const char* name;    // file name, e.g. "particle.vert"
  const char* source;
};
extern const EmbeddedShader kEmbeddedShaders[];
extern const int kEmbeddedShaderCount;

/// The source of a shader file by name; throws std::runtime_error if unknown.
std::string shader_source(std::string_view name);
/// Names of every embedded shader.
std::vector<std::string> shader_names();

/// Compiles one stage; throws std::runtime_error with the info log on failure.
GLuint compile_shader(GLenum stage, std::string_view name, const std::string& source);
/// Stage from the file extension (.vert, .frag, .comp, .geom).
GLenum shader_stage(std::string_view name);

class Program {
 public:
  Program() = default;
  /// Links the named stages, e.g. {"particle.vert", "particle.frag"}.
  explicit Program(const std::vector<std::string>& stage_files);
  ~Program();
  Program(Program&& o) noexcept : id_(o.id_) { o.id_ = 0; }
  Program& operator=(Program&& o) noexcept;
  Program(const Program&) = delete;
  Program& operator=(const Program&) = delete;

  GLuint id() const { return id_; }
  void use() const { glUseProgram(id_); }
  GLint loc(const char* uniform) const { return glGetUniformLocation(id_, uniform); }

 private:
  GLuint id_ = 0;
};

}  // namespace rtsph::render
