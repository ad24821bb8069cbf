// CSV: one row per fluid particle, in id order. The all-attributes header is fixed by the
// foundation spec (x,y[,z],vx,vy[,vz],density,pressure), so there is no id column.
#include <charconv>

#include <fmt/format.h>

#include "io/atomic_file.h"
#include "io/formats.h"
#include "io/frame_index.h"
#include "io/particle_order.h"

namespace rtsph::io {
namespace {

class CsvExporter final : public Exporter {
 public:
  CsvExporter(const std::filesystem::path& dir, const ExportOptions& o) : options_(o), index_(dir, o.resume) {}

  void write_frame(int frame, double time_s, const ParticleView& view) override {
    check_view(view, options_);
    const auto name = frame_file_name(frame, "csv");
    write_file_atomic(index_.dir() / name, [&](std::ostream& os) { write_body(os, view); });
    index_.add(frame, time_s, name);
  }

 private:
  void write_body(std::ostream& os, const ParticleView& view) const {
    static constexpr const char* kAxis[] = {"x", "y", "z"};
    const int d = view.dim;
    std::vector<const float*> cols;
    fmt::memory_buffer buf;
    auto out = std::back_inserter(buf);
    auto column = [&](const std::string& name, const float* data) {
      fmt::format_to(out, "{}{}", cols.empty() ? "" : ",", name);
      cols.push_back(data);
    };
    for (int k = 0; k < d; ++k) column(kAxis[k], view.x[k]);
    if (options_.velocity)
      for (int k = 0; k < d; ++k) column(fmt::format("v{}", kAxis[k]), view.v[k]);
    if (options_.density) column("density", view.density);
    if (options_.pressure) column("pressure", view.pressure);
    buf.push_back('\n');
    char text[32];
    for (auto i : id_order(view)) {
      for (std::size_t c = 0; c < cols.size(); ++c) {
        if (c) buf.push_back(',');
        // Shortest text that reads back as the same float; to_chars is several times faster
        // than fmt here, which matters at millions of values per frame.
        auto end = std::to_chars(text, text + sizeof text, cols[c][i]).ptr;
        buf.append(text, end);
      }
      buf.push_back('\n');
      if (buf.size() > (1u << 20)) {
        os.write(buf.data(), static_cast<std::streamsize>(buf.size()));
        buf.clear();
      }
    }
    os.write(buf.data(), static_cast<std::streamsize>(buf.size()));
  }

  ExportOptions options_;
  FrameIndex index_;
};

}  // namespace

std::unique_ptr<Exporter> make_csv_exporter(const std::filesystem::path& dir, const ExportOptions& options) {
  return std::make_unique<CsvExporter>(dir, options);
}

}  // namespace rtsph::io
