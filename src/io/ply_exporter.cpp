// Binary little-endian PLY: one vertex per fluid particle, in id order. Blender, Houdini and
// MeshLab import it as a point cloud with the extra properties as point attributes.
#include <fmt/format.h>

#include "io/atomic_file.h"
#include "io/binary_out.h"  // little-endian host assumption
#include "io/formats.h"
#include "io/frame_index.h"
#include "io/particle_order.h"

namespace rtsph::io {
namespace {

class PlyExporter final : public Exporter {
 public:
  PlyExporter(const std::filesystem::path& dir, const ExportOptions& o) : options_(o), index_(dir, o.resume) {}

  void write_frame(int frame, double time_s, const ParticleView& view) override {
    check_view(view, options_);
    const auto name = frame_file_name(frame, "ply");
    write_file_atomic(index_.dir() / name, [&](std::ostream& os) { write_ply(os, frame, time_s, view); });
    index_.add(frame, time_s, name);
  }

 private:
  void write_ply(std::ostream& os, int frame, double time_s, const ParticleView& view) const {
    static const float kZero = 0.0f;
    // Float columns in file order; a null source with stride 0 writes zeros (z in 2D).
    struct Column { const float* data; std::size_t stride; };
    std::vector<Column> cols;
    fmt::memory_buffer head;
    auto out = std::back_inserter(head);
    fmt::format_to(out, "ply\nformat binary_little_endian 1.0\ncomment rtsph frame {} time_s {}\nelement vertex {}\n",
                   frame, time_s, view.count);
    auto vec3 = [&](const char* prefix, const float* const* src) {
      static constexpr const char* kAxis[] = {"x", "y", "z"};
      for (int k = 0; k < 3; ++k) {
        fmt::format_to(out, "property float {}{}\n", prefix, kAxis[k]);
        cols.push_back(k < view.dim ? Column{src[k], 1} : Column{&kZero, 0});
      }
    };
    vec3("", view.x);
    if (options_.velocity) vec3("v", view.v);
    if (options_.density) {
      fmt::format_to(out, "property float density\n");
      cols.push_back({view.density, 1});
    }
    if (options_.pressure) {
      fmt::format_to(out, "property float pressure\n");
      cols.push_back({view.pressure, 1});
    }
    if (options_.id) fmt::format_to(out, "property uint id\n");
    fmt::format_to(out, "end_header\n");
    os.write(head.data(), static_cast<std::streamsize>(head.size()));

    const std::size_t record = 4 * cols.size() + (options_.id ? 4 : 0);
    std::vector<char> chunk;
    chunk.reserve(record * 4096);
    for (auto i : id_order(view)) {
      for (const auto& c : cols) {
        const char* p = reinterpret_cast<const char*>(&c.data[i * c.stride]);
        chunk.insert(chunk.end(), p, p + 4);
      }
      if (options_.id) {
        const char* p = reinterpret_cast<const char*>(&view.id[i]);
        chunk.insert(chunk.end(), p, p + 4);
      }
      if (chunk.size() >= record * 4096) {
        os.write(chunk.data(), static_cast<std::streamsize>(chunk.size()));
        chunk.clear();
      }
    }
    os.write(chunk.data(), static_cast<std::streamsize>(chunk.size()));
  }

  ExportOptions options_;
  FrameIndex index_;
};

}  // namespace

std::unique_ptr<Exporter> make_ply_exporter(const std::filesystem::path& dir, const ExportOptions& options) {
  return std::make_unique<PlyExporter>(dir, options);
}

}  // namespace rtsph::io
