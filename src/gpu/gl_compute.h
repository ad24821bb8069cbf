#pragma once
// Thin OpenGL compute plumbing for the GPU backend: buffers, compute programs assembled from
// shaders/gpu/ with the shared layout (layout.h) prepended, and dispatch with the barrier every
// pass needs. Everything here requires a current OpenGL 4.3+ context on the calling thread.
#include <epoxy/gl.h>

#include <cstddef>
#include <string>
#include <vector>

namespace rtsph::gpu {

/// A shader source embedded into the binary (shaders/embed.cmake).
struct EmbeddedSource {
  const char* name;
  const char* source;
};
extern const EmbeddedSource kEmbeddedShaders[];
extern const int kEmbeddedShaderCount;

/// One shader storage buffer; grows (discarding its contents) through reserve().
class Buffer {
 public:
  Buffer() = default;
  ~Buffer();
  Buffer(Buffer&& o) noexcept : id_(o.id_), bytes_(o.bytes_) { o.id_ = 0; o.bytes_ = 0; }
  Buffer& operator=(Buffer&& o) noexcept;
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;

  /// Makes room for at least `bytes` (contents undefined after a reallocation).
  void reserve(std::size_t bytes);
  void upload(const void* data, std::size_t bytes, std::size_t offset = 0);
  void download(void* data, std::size_t bytes, std::size_t offset = 0) const;
  void bind(GLuint binding) const { glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, id_); }
  void fill_zero();
  GLuint id() const { return id_; }
  std::size_t bytes() const { return bytes_; }
  void swap(Buffer& o) noexcept { std::swap(id_, o.id_); std::swap(bytes_, o.bytes_); }

 private:
  GLuint id_ = 0;
  std::size_t bytes_ = 0;
};

/// A compute program: `#version 450`, the given #defines, layout.h, common.glsl, then the file.
class ComputeProgram {
 public:
  ComputeProgram() = default;
  ComputeProgram(const std::string& file, const std::vector<std::string>& defines);
  ~ComputeProgram();
  ComputeProgram(ComputeProgram&& o) noexcept : id_(o.id_) { o.id_ = 0; }
  ComputeProgram& operator=(ComputeProgram&& o) noexcept;
  ComputeProgram(const ComputeProgram&) = delete;
  ComputeProgram& operator=(const ComputeProgram&) = delete;

  GLuint id() const { return id_; }
  void set(const char* name, GLuint v) const;
  void set(const char* name, GLint v) const;
  void set(const char* name, float v) const;
  /// Runs ceil(items / RTSPH_WG) workgroups, then a storage and uniform barrier.
  void dispatch(std::size_t items) const;
  void dispatch_groups(GLuint groups) const;

 private:
  GLuint id_ = 0;
};

/// The full source handed to the GL compiler (for errors and tests).
std::string compute_source(const std::string& file, const std::vector<std::string>& defines);
/// Names of the embedded GPU compute shaders.
std::vector<std::string> compute_shader_names();

/// Null when the current context can run the backend, else one line saying why (no context,
/// GL older than 4.3, too few storage blocks).
std::string compute_support_problem();

}  // namespace rtsph::gpu
