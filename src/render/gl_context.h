#pragma once
// Headless OpenGL through EGL (no X display): Mesa's surfaceless platform first, then the EGL
// device platform (NVIDIA and other drivers), then the default display. The context is core
// profile 4.5 or 4.3 and current on the creating thread, with no surface: render into an FBO.
#include <memory>
#include <string>

namespace rtsph::render {

class HeadlessContext {
 public:
  /// Null (and a one-line reason in *error) when no EGL display or no GL 4.3 core context can be
  /// made. `no_display` is set when not even an EGL display could be initialised (tests skip
  /// then; any other failure is an error).
  static std::unique_ptr<HeadlessContext> create(std::string* error, bool* no_display = nullptr);
  ~HeadlessContext();
  HeadlessContext(const HeadlessContext&) = delete;
  HeadlessContext& operator=(const HeadlessContext&) = delete;

  void make_current();
  /// Makes no context current on this thread (so that another thread may make this one current).
  void release();
  /// e.g. "EGL surfaceless, OpenGL 4.5 (Core Profile) Mesa 23.2.1, llvmpipe (LLVM 15.0.7, 256 bits)".
  const std::string& description() const { return description_; }

 private:
  HeadlessContext() = default;
  void* display_ = nullptr;
  void* context_ = nullptr;
  std::string description_;
};

/// "OpenGL <version>, <renderer>" of the current context.
std::string gl_description();
/// True when the current context is at least OpenGL 4.3.
bool gl_version_at_least_43();

}  // namespace rtsph::render
