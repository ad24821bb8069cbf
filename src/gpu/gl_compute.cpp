#include "gpu/gl_compute.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>

#include "gpu/layout.h"

namespace rtsph::gpu {


namespace {
std::string source_of(const std::string& name) {
  // RTSPH_SHADER_DIR (the renderer's override for editing shaders) also serves shaders/gpu/.
  if (const char* dir = std::getenv("RTSPH_SHADER_DIR"); dir && *dir && name != "layout.h") {
    std::ifstream in(fmt::format("{}/gpu/{}", dir, name));
    if (in) {
      std::stringstream ss;
      ss << in.rdbuf();
      return ss.str();
    }
  }
  for (int i = 0; i < kEmbeddedShaderCount; ++i)
    if (name == kEmbeddedShaders[i].name) return kEmbeddedShaders[i].source;
  throw std::runtime_error(fmt::format("unknown GPU shader '{}'", name));
}
}  // namespace

Buffer::~Buffer() {
  if (id_) glDeleteBuffers(1, &id_);
}

Buffer& Buffer::operator=(Buffer&& o) noexcept {
  if (this != &o) {
    if (id_) glDeleteBuffers(1, &id_);
    id_ = o.id_;
    bytes_ = o.bytes_;
    o.id_ = 0;
    o.bytes_ = 0;
  }
  return *this;
}

void Buffer::reserve(std::size_t bytes) {
  bytes = std::max<std::size_t>(bytes, 16);
  if (id_ && bytes <= bytes_) return;
  if (id_) glDeleteBuffers(1, &id_);
  glCreateBuffers(1, &id_);
  // Room to grow by half again, so emitters' slowly growing counts do not reallocate each step.
  const std::size_t size = bytes_ ? bytes + bytes / 2 : bytes;
  glNamedBufferData(id_, GLsizeiptr(size), nullptr, GL_DYNAMIC_DRAW);
  if (glGetError() == GL_OUT_OF_MEMORY)
    throw std::length_error(fmt::format("GPU buffer of {} bytes: out of GPU memory", size));
  bytes_ = size;
}

void Buffer::upload(const void* data, std::size_t bytes, std::size_t offset) {
  if (bytes == 0) return;
  if (offset + bytes > bytes_) throw std::logic_error("Buffer::upload past the end");
  glNamedBufferSubData(id_, GLintptr(offset), GLsizeiptr(bytes), data);
}

void Buffer::download(void* data, std::size_t bytes, std::size_t offset) const {
  if (bytes == 0) return;
  if (offset + bytes > bytes_) throw std::logic_error("Buffer::download past the end");
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  glGetNamedBufferSubData(id_, GLintptr(offset), GLsizeiptr(bytes), data);
}

void Buffer::fill_zero() {
  const GLuint zero = 0;
  glClearNamedBufferData(id_, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
}

std::string compute_source(const std::string& file, const std::vector<std::string>& defines) {
  std::string s = "#version 450\n";
  for (const auto& d : defines) s += "#define " + d + "\n";
  s += "layout(local_size_x = RTSPH_WG_SIZE) in;\n";
  s += source_of("layout.h");
  s += "\n#line 1 1\n" + source_of("common.glsl");
  s += "\n#line 1 2\n" + source_of(file);
  return s;
}

std::vector<std::string> compute_shader_names() {
  std::vector<std::string> out;
  for (int i = 0; i < kEmbeddedShaderCount; ++i) {
    const std::string n = kEmbeddedShaders[i].name;
    if (n.size() > 5 && n.substr(n.size() - 5) == ".comp") out.push_back(n);
  }
  return out;
}

ComputeProgram::ComputeProgram(const std::string& file, const std::vector<std::string>& defines) {
  std::vector<std::string> defs = defines;
  defs.push_back(fmt::format("RTSPH_WG_SIZE {}", RTSPH_WG));
  const std::string src = compute_source(file, defs);
  GLuint sh = glCreateShader(GL_COMPUTE_SHADER);
  const char* p = src.c_str();
  glShaderSource(sh, 1, &p, nullptr);
  glCompileShader(sh);
  GLint ok = 0;
  glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
  auto log_of = [](GLuint obj, bool program) {
    GLint len = 0;
    if (program) glGetProgramiv(obj, GL_INFO_LOG_LENGTH, &len);
    else glGetShaderiv(obj, GL_INFO_LOG_LENGTH, &len);
    std::string log(std::size_t(std::max(len, 1)), '\0');
    if (program) glGetProgramInfoLog(obj, len, nullptr, log.data());
    else glGetShaderInfoLog(obj, len, nullptr, log.data());
    return std::string(log.c_str());
  };
  if (!ok) {
    const std::string log = log_of(sh, false);
    glDeleteShader(sh);
    // File 1 is common.glsl, file 2 the shader itself (#line directives above).
    throw std::runtime_error(fmt::format("GPU shader {} failed to compile (file 1 = common.glsl, 2 = {}): {}",
                                         file, file, log));
  }
  id_ = glCreateProgram();
  glAttachShader(id_, sh);
  glLinkProgram(id_);
  glDetachShader(id_, sh);
  glDeleteShader(sh);
  glGetProgramiv(id_, GL_LINK_STATUS, &ok);
  if (!ok) {
    const std::string log = log_of(id_, true);
    glDeleteProgram(id_);
    id_ = 0;
    throw std::runtime_error(fmt::format("GPU shader {} failed to link: {}", file, log));
  }
}

ComputeProgram::~ComputeProgram() {
  if (id_) glDeleteProgram(id_);
}

ComputeProgram& ComputeProgram::operator=(ComputeProgram&& o) noexcept {
  if (this != &o) {
    if (id_) glDeleteProgram(id_);
    id_ = o.id_;
    o.id_ = 0;
  }
  return *this;
}

void ComputeProgram::set(const char* name, GLuint v) const {
  glProgramUniform1ui(id_, glGetUniformLocation(id_, name), v);
}
void ComputeProgram::set(const char* name, GLint v) const {
  glProgramUniform1i(id_, glGetUniformLocation(id_, name), v);
}
void ComputeProgram::set(const char* name, float v) const {
  glProgramUniform1f(id_, glGetUniformLocation(id_, name), v);
}

void ComputeProgram::dispatch(std::size_t items) const {
  if (items == 0) return;
  dispatch_groups(GLuint((items + RTSPH_WG - 1) / RTSPH_WG));
}

void ComputeProgram::dispatch_groups(GLuint groups) const {
  if (groups == 0) return;
  glUseProgram(id_);
  glDispatchCompute(groups, 1, 1);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_UNIFORM_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

std::string compute_support_problem() {
  const int version = epoxy_gl_version();
  if (version < 43 || epoxy_is_desktop_gl() == 0)
    return fmt::format("the GPU backend needs desktop OpenGL 4.3 compute shaders; this context has {} {}.{}",
                       epoxy_is_desktop_gl() ? "OpenGL" : "OpenGL ES", version / 10, version % 10);
  GLint bindings = 0, blocks = 0;
  glGetIntegerv(GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS, &bindings);
  glGetIntegerv(GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS, &blocks);
  if (bindings < RTSPH_BINDINGS || blocks < 14)
    return fmt::format("the GPU backend needs {} storage buffer bindings and 14 per compute shader; "
                       "this OpenGL has {} and {}", RTSPH_BINDINGS, bindings, blocks);
  return {};
}

}  // namespace rtsph::gpu
