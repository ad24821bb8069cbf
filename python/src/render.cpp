// rtsph.render: one frame of a simulation, drawn headless through EGL by the renderer that
// `rtsph render` uses, returned as an (H, W, 4) uint8 array and optionally written as PNG.
#include <fmt/format.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/string.h>

#include <cerrno>
#include <cstring>
#include <mutex>
#include <vector>

#include "binding.h"

#ifdef RTSPH_HAVE_RENDER
#include "apps/viewer/scene_view.h"
#include "render/gl_context.h"
#include "render/image_io.h"
#include "render/renderer.h"
#endif

namespace rtsph::py {

using Image = nb::ndarray<nb::numpy, std::uint8_t>;

Image render_frame(PySimulation& self, int width, int height, const std::string& color,
                   const std::string& display, const std::string& colormap, const std::string& style,
                   const std::string& path) {
#ifndef RTSPH_HAVE_RENDER
  (void)self; (void)width; (void)height; (void)color; (void)display; (void)colormap; (void)style; (void)path;
  throw std::runtime_error("render: this build of rtsph has no renderer (RTSPH_BUILD_VIEWER=OFF)");
#else
  if (width < 16 || height < 16 || width > 8192 || height > 8192)
    throw std::invalid_argument(fmt::format("render: size {}x{} is outside 16..8192", width, height));
  render::RenderSettings settings;
  if (!render::parse_color_mode(color, &settings.color))
    throw std::invalid_argument(fmt::format("render: color '{}': expected solid, speed, velocity, pressure, density or log_density", color));
  if (!render::parse_display_mode(display, &settings.display))
    throw std::invalid_argument(fmt::format("render: display '{}': expected fluid, obstacles or all", display));
  if (!render::parse_colormap(colormap, &settings.map))
    throw std::invalid_argument(fmt::format("render: colormap '{}': expected viridis or turbo", colormap));
  if (!render::parse_style(style, &settings.style))
    throw std::invalid_argument(fmt::format("render: style '{}': expected surface or particles", style));
  auto* pixels = new std::vector<unsigned char>();
  nb::capsule owner(pixels, [](void* p) noexcept { delete static_cast<std::vector<unsigned char>*>(p); });
  {
    nb::gil_scoped_release release;
    Lock lock(self.mutex);  // a GPU simulation's context is now current: draw from its buffers
    if (!self.sim) throw std::runtime_error("the simulation was closed");
    // A CPU simulation gets a context per call: cheap next to drawing on llvmpipe, and it keeps
    // no GL state alive between calls or tied to one Python thread.
    std::string err;
    std::unique_ptr<render::HeadlessContext> ctx;
    if (self.backend != "gpu") {
      ctx = render::HeadlessContext::create(&err);
      if (!ctx) throw std::runtime_error("render: " + err);
    }
    const SimSpec& spec = self.sim->spec();
    render::Renderer renderer;
    app::setup_scene_view(spec, renderer, settings);
    render::Camera cam;
    app::frame_scene(spec, cam, float(width) / float(height));
    render::OffscreenTarget target(width, height);
    const BoundaryView boundary = self.sim->boundary();
    if (const auto device = self.sim->device_particles())
      renderer.use_device(*device, &boundary);
    else
      renderer.upload(self.sim->fluid(), &boundary);
    renderer.upload_solids(app::obstacle_solids(*self.sim));
    target.bind();
    renderer.draw(cam, width, height, settings);
    *pixels = target.read_rgba();
    errno = 0;  // stb_image_write reports through fopen's errno
    if (!path.empty() && !render::write_png(path, width, height, pixels->data())) {
      const int err = errno;
      throw io::IoError(err ? fmt::format("render: cannot write {}: {}", path, std::strerror(err))
                            : fmt::format("render: cannot write {}", path));
    }
  }
  const std::size_t shape[3] = {std::size_t(height), std::size_t(width), 4};
  return Image(pixels->data(), 3, shape, owner);
#endif
}

void bind_render(nb::module_& m) {
  m.def("_render", &render_frame, nb::arg("sim"), nb::arg("width"), nb::arg("height"), nb::arg("color"),
        nb::arg("display"), nb::arg("colormap"), nb::arg("style"), nb::arg("path"));
}

}  // namespace rtsph::py
