// VTK XML PolyData (.vtp) with raw appended binary data, plus DIR/frames.pvd so ParaView opens
// the run as one time series. Each point is also a Verts cell: without cells ParaView's
// Surface representation shows nothing.
#include <fmt/format.h>

#include <functional>
#include <limits>

#include "io/atomic_file.h"
#include "io/binary_out.h"
#include "io/formats.h"
#include "io/frame_index.h"
#include "io/particle_order.h"

namespace rtsph::io {
namespace {

/// One DataArray of the appended block: its XML tag attributes and how to produce its bytes.
struct Array {
  std::string section;  // "PointData", "Points" or "Verts"
  std::string type, name;
  int components;
  std::size_t bytes;
  std::function<void(std::ostream&)> write;
};

template <class T, class F>
std::function<void(std::ostream&)> gathered(std::size_t n, F value) {
  return [n, value](std::ostream& os) {
    std::vector<T> out(n);
    for (std::size_t j = 0; j < n; ++j) out[j] = value(j);
    write_raw(os, out);
  };
}

class VtkExporter final : public Exporter {
 public:
  VtkExporter(const std::filesystem::path& dir, const ExportOptions& o) : options_(o), index_(dir, o.resume) {}

  void write_frame(int frame, double time_s, const ParticleView& view) override {
    check_view(view, options_);
    if (view.count > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max())) {
      throw IoError(fmt::format("vtk: {} particles exceed the Int32 cell arrays", view.count));
    }
    const auto name = frame_file_name(frame, "vtp");
    write_file_atomic(index_.dir() / name, [&](std::ostream& os) { write_vtp(os, view); });
    index_.add(frame, time_s, name);
    write_pvd();
  }

 private:
  std::vector<Array> arrays(const ParticleView& view, const std::vector<std::uint32_t>& order) const {
    const std::size_t n = view.count;
    const int d = view.dim;
    auto vec3 = [&](const float* const* src) {
      return gathered<float>(3 * n, [&view, &order, src, d](std::size_t j) {
        int k = static_cast<int>(j % 3);
        return k < d ? src[k][order[j / 3]] : 0.0f;
      });
    };
    auto scalar = [&](const float* src) {
      return gathered<float>(n, [&order, src](std::size_t j) { return src[order[j]]; });
    };
    std::vector<Array> a;
    if (options_.velocity) a.push_back({"PointData", "Float32", "velocity", 3, 12 * n, vec3(view.v)});
    if (options_.density) a.push_back({"PointData", "Float32", "density", 1, 4 * n, scalar(view.density)});
    if (options_.pressure) a.push_back({"PointData", "Float32", "pressure", 1, 4 * n, scalar(view.pressure)});
    if (options_.id) {
      a.push_back({"PointData", "UInt32", "id", 1, 4 * n,
                   gathered<std::uint32_t>(n, [&order, &view](std::size_t j) { return view.id[order[j]]; })});
    }
    a.push_back({"Points", "Float32", "Points", 3, 12 * n, vec3(view.x)});
    // Int32 cell arrays: ids are 32-bit anyway, and Int64 would add 16 bytes per particle.
    a.push_back({"Verts", "Int32", "connectivity", 1, 4 * n,
                 gathered<std::int32_t>(n, [](std::size_t j) { return static_cast<std::int32_t>(j); })});
    a.push_back({"Verts", "Int32", "offsets", 1, 4 * n,
                 gathered<std::int32_t>(n, [](std::size_t j) { return static_cast<std::int32_t>(j + 1); })});
    return a;
  }

  void write_vtp(std::ostream& os, const ParticleView& view) const {
    const auto order = id_order(view);
    const auto list = arrays(view, order);
    fmt::memory_buffer xml;
    auto out = std::back_inserter(xml);
    fmt::format_to(out,
                   "<?xml version=\"1.0\"?>\n"
                   "<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
                   "  <PolyData>\n"
                   "    <Piece NumberOfPoints=\"{0}\" NumberOfVerts=\"{0}\" NumberOfLines=\"0\" NumberOfStrips=\"0\" "
                   "NumberOfPolys=\"0\">\n",
                   view.count);
    std::uint64_t offset = 0;
    std::string open;
    for (const auto& a : list) {
      if (a.section != open) {
        if (!open.empty()) fmt::format_to(out, "      </{}>\n", open);
        open = a.section;
        fmt::format_to(out, "      <{}>\n", open);
      }
      fmt::format_to(out, "        <DataArray type=\"{}\" Name=\"{}\"", a.type, a.name);
      if (a.components != 1) fmt::format_to(out, " NumberOfComponents=\"{}\"", a.components);
      fmt::format_to(out, " format=\"appended\" offset=\"{}\"/>\n", offset);
      offset += sizeof(std::uint64_t) + a.bytes;
    }
    fmt::format_to(out, "      </{}>\n    </Piece>\n  </PolyData>\n  <AppendedData encoding=\"raw\">\n   _", open);
    os.write(xml.data(), static_cast<std::streamsize>(xml.size()));
    for (const auto& a : list) {
      write_raw(os, static_cast<std::uint64_t>(a.bytes));
      a.write(os);
    }
    os << "\n  </AppendedData>\n</VTKFile>\n";
  }

  void write_pvd() const {
    fmt::memory_buffer xml;
    auto out = std::back_inserter(xml);
    fmt::format_to(out,
                   "<?xml version=\"1.0\"?>\n"
                   "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
                   "  <Collection>\n");
    for (const auto& e : index_.entries()) {
      fmt::format_to(out, "    <DataSet timestep=\"{}\" group=\"\" part=\"0\" file=\"{}\"/>\n", e.time_s, e.file);
    }
    fmt::format_to(out, "  </Collection>\n</VTKFile>\n");
    write_file_atomic(index_.dir() / "frames.pvd", std::string_view(xml.data(), xml.size()));
  }

  ExportOptions options_;
  FrameIndex index_;
};

}  // namespace

std::unique_ptr<Exporter> make_vtk_exporter(const std::filesystem::path& dir, const ExportOptions& options) {
  return std::make_unique<VtkExporter>(dir, options);
}

}  // namespace rtsph::io
