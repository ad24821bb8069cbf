#include "render/gl_context.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <cstring>
#include <vector>

#include <fmt/format.h>

namespace rtsph::render {

namespace {

bool has_extension(const char* list, const char* ext) {
  if (!list) return false;
  std::size_t n = std::strlen(ext);
  for (const char* p = list; (p = std::strstr(p, ext)) != nullptr; p += n)
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

struct Candidate {
  std::string name;
  EGLDisplay display;
};

// Creates a core context of at least 4.3 on an initialised display; EGL_NO_CONTEXT on failure.
EGLContext create_core_context(EGLDisplay dpy, std::string* why) {
  if (!eglBindAPI(EGL_OPENGL_API)) {
    *why = "eglBindAPI(EGL_OPENGL_API) failed";
    return EGL_NO_CONTEXT;
  }
  const char* exts = eglQueryString(dpy, EGL_EXTENSIONS);
  EGLConfig config = nullptr;
  if (!has_extension(exts, "EGL_KHR_no_config_context") &&
      !has_extension(exts, "EGL_MESA_configless_context")) {
    const EGLint attrs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, EGL_DONT_CARE,
                            EGL_NONE};
    EGLint n = 0;
    if (!eglChooseConfig(dpy, attrs, &config, 1, &n) || n < 1) {
      *why = "no EGL config supports desktop OpenGL";
      return EGL_NO_CONTEXT;
    }
  }
  for (int minor : {6, 5, 3}) {
    const EGLint ctx_attrs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, minor,
                                EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    EGLContext ctx = eglCreateContext(dpy, config, EGL_NO_CONTEXT, ctx_attrs);
    if (ctx != EGL_NO_CONTEXT) return ctx;
  }
  *why = "the driver offers no OpenGL 4.3 core context";
  return EGL_NO_CONTEXT;
}

}  // namespace

std::string gl_description() {
  const char* ver = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  const char* ren = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  return fmt::format("OpenGL {}, {}", ver ? ver : "?", ren ? ren : "?");
}

bool gl_version_at_least_43() { return epoxy_is_desktop_gl() && epoxy_gl_version() >= 43; }

std::unique_ptr<HeadlessContext> HeadlessContext::create(std::string* error, bool* no_display) {
  if (no_display) *no_display = false;
  const char* client_exts = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
  std::vector<std::string> reasons;
  bool any_display = false;

  auto try_display = [&](const std::string& name,
                         EGLDisplay dpy) -> std::unique_ptr<HeadlessContext> {
    if (dpy == EGL_NO_DISPLAY) {
      reasons.push_back(name + ": no display");
      return nullptr;
    }
    EGLint major = 0, minor = 0;
    if (!eglInitialize(dpy, &major, &minor)) {
      reasons.push_back(name + ": eglInitialize failed");
      return nullptr;
    }
    any_display = true;
    std::string why;
    EGLContext ctx = create_core_context(dpy, &why);
    if (ctx == EGL_NO_CONTEXT) {
      reasons.push_back(name + ": " + why);
      eglTerminate(dpy);
      return nullptr;
    }
    if (!eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
      reasons.push_back(name + ": eglMakeCurrent without a surface failed");
      eglDestroyContext(dpy, ctx);
      eglTerminate(dpy);
      return nullptr;
    }
    if (epoxy_gl_version() < 43) {
      reasons.push_back(fmt::format("{}: OpenGL {}.{} < 4.3", name, epoxy_gl_version() / 10,
                                    epoxy_gl_version() % 10));
      eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      eglDestroyContext(dpy, ctx);
      eglTerminate(dpy);
      return nullptr;
    }
    std::unique_ptr<HeadlessContext> c(new HeadlessContext);
    c->display_ = dpy;
    c->context_ = ctx;
    c->description_ = fmt::format("EGL {}, {}", name, gl_description());
    return c;
  };

  if (get_platform_display && has_extension(client_exts, "EGL_MESA_platform_surfaceless")) {
    if (auto c = try_display("surfaceless",
                             get_platform_display(EGL_PLATFORM_SURFACELESS_MESA,
                                                  EGL_DEFAULT_DISPLAY, nullptr)))
      return c;
  }
  if (get_platform_display && has_extension(client_exts, "EGL_EXT_platform_device")) {
    auto query_devices =
        reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    if (query_devices) {
      EGLDeviceEXT devices[16];
      EGLint n = 0;
      if (query_devices(16, devices, &n)) {
        for (EGLint i = 0; i < n; ++i) {
          if (auto c = try_display(fmt::format("device {}", i),
                                   get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[i],
                                                        nullptr)))
            return c;
        }
      }
    }
  }
  if (auto c = try_display("default display", eglGetDisplay(EGL_DEFAULT_DISPLAY))) return c;

  std::string joined;
  for (const auto& r : reasons) joined += (joined.empty() ? "" : "; ") + r;
  if (error)
    *error = fmt::format("cannot create a headless OpenGL 4.3 core context through EGL ({})",
                         joined.empty() ? "no EGL platform available" : joined);
  if (no_display) *no_display = !any_display;
  return nullptr;
}

HeadlessContext::~HeadlessContext() {
  auto dpy = static_cast<EGLDisplay>(display_);
  eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(dpy, static_cast<EGLContext>(context_));
  // No eglTerminate: an EGL display is one per process and platform, so terminating it would
  // pull it from under any other HeadlessContext. (Mesa unloads its driver on terminate, as after
  // the failed probes in create(); leak-checked builds keep driver modules loaded so that
  // LeakSanitizer can name them: tests/support/keep_modules_loaded.cpp.)
  eglReleaseThread();
}

void HeadlessContext::make_current() {
  eglMakeCurrent(static_cast<EGLDisplay>(display_), EGL_NO_SURFACE, EGL_NO_SURFACE,
                 static_cast<EGLContext>(context_));
}

void HeadlessContext::release() {
  eglMakeCurrent(static_cast<EGLDisplay>(display_), EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
}

}  // namespace rtsph::render
