// The surface formats: one file per frame holding the fluid's surface instead of its particles
// (surface.h builds it with OpenVDB). `vdb`: the level set and a fog volume, for Houdini's and
// Blender's volume tools. `obj` and `ply-mesh`: a closed triangle mesh with vertex normals, for
// anything that reads meshes. Frames, index.csv and atomic writes work as for the particle formats.
#include <fmt/format.h>

#include "io/atomic_file.h"
#include "io/binary_out.h"  // little-endian host assumption
#include "io/formats.h"
#include "io/frame_index.h"
#include "io/surface.h"

namespace rtsph::io {
namespace {

class SurfaceExporter : public Exporter {
 public:
  SurfaceExporter(const std::filesystem::path& dir, const ExportOptions& o, std::string extension)
      : options_(o.surface), extension_(std::move(extension)), index_(dir, o.resume) {}

  void write_frame(int frame, double time_s, const ParticleView& view) override {
    const FluidLevelSet surface(view, options_);
    const auto name = frame_file_name(frame, extension_);
    write(index_.dir() / name, surface, frame, time_s);
    index_.add(frame, time_s, name);
  }

 protected:
  virtual void write(const std::filesystem::path& path, const FluidLevelSet& surface, int frame, double time_s) = 0;
  SurfaceOptions options_;

 private:
  std::string extension_;
  FrameIndex index_;
};

class VdbExporter final : public SurfaceExporter {
 public:
  VdbExporter(const std::filesystem::path& dir, const ExportOptions& o) : SurfaceExporter(dir, o, "vdb") {}

 private:
  void write(const std::filesystem::path& path, const FluidLevelSet& surface, int frame, double time_s) override {
    write_file_atomic_via_path(path, [&](const std::filesystem::path& tmp) { surface.write_vdb(tmp, frame, time_s); });
  }
};

/// Wavefront OBJ, text: `v`, `vn` and `f a//a b//b c//c` (1-based; each vertex's normal has
/// its index). Numbers are the shortest text that reads back as the same float.
class ObjExporter final : public SurfaceExporter {
 public:
  ObjExporter(const std::filesystem::path& dir, const ExportOptions& o) : SurfaceExporter(dir, o, "obj") {}

 private:
  void write(const std::filesystem::path& path, const FluidLevelSet& surface, int frame, double time_s) override {
    const SurfaceMesh m = surface.mesh(options_.adaptivity);
    write_file_atomic(path, [&](std::ostream& os) {
      fmt::memory_buffer buf;
      auto out = std::back_inserter(buf);
      auto flush = [&](std::size_t above) {
        if (buf.size() < above) return;
        os.write(buf.data(), static_cast<std::streamsize>(buf.size()));
        buf.clear();
      };
      fmt::format_to(out, "# rtsph frame {} time_s {}: fluid surface, {} vertices, {} triangles\no fluid\n", frame,
                     time_s, m.vertex_count(), m.triangle_count());
      const float* p = m.points.data();
      for (std::size_t i = 0; i < m.vertex_count(); ++i, p += 3) {
        fmt::format_to(out, "v {} {} {}\n", p[0], p[1], p[2]);
        flush(1 << 16);
      }
      const float* n = m.normals.data();
      for (std::size_t i = 0; i < m.vertex_count(); ++i, n += 3) {
        fmt::format_to(out, "vn {} {} {}\n", n[0], n[1], n[2]);
        flush(1 << 16);
      }
      const auto* t = m.triangles.data();
      for (std::size_t i = 0; i < m.triangle_count(); ++i, t += 3) {
        fmt::format_to(out, "f {0}//{0} {1}//{1} {2}//{2}\n", t[0] + 1, t[1] + 1, t[2] + 1);
        flush(1 << 16);
      }
      flush(0);
    });
  }
};

/// Binary little-endian PLY with faces: `vertex` (x y z nx ny nz, float) and `face`
/// (`list uchar uint vertex_indices`, three each), the layout Blender, MeshLab and trimesh read.
class PlyMeshExporter final : public SurfaceExporter {
 public:
  PlyMeshExporter(const std::filesystem::path& dir, const ExportOptions& o) : SurfaceExporter(dir, o, "ply") {}

 private:
  void write(const std::filesystem::path& path, const FluidLevelSet& surface, int frame, double time_s) override {
    const SurfaceMesh m = surface.mesh(options_.adaptivity);
    write_file_atomic(path, [&](std::ostream& os) {
      const std::string head = fmt::format(
          "ply\nformat binary_little_endian 1.0\ncomment rtsph frame {} time_s {}: fluid surface\n"
          "element vertex {}\nproperty float x\nproperty float y\nproperty float z\n"
          "property float nx\nproperty float ny\nproperty float nz\n"
          "element face {}\nproperty list uchar uint vertex_indices\nend_header\n",
          frame, time_s, m.vertex_count(), m.triangle_count());
      os.write(head.data(), static_cast<std::streamsize>(head.size()));
      std::vector<char> chunk;
      chunk.reserve(1 << 16);
      auto put = [&](const void* data, std::size_t bytes) {
        const char* c = static_cast<const char*>(data);
        chunk.insert(chunk.end(), c, c + bytes);
        if (chunk.size() >= (1 << 16)) {
          os.write(chunk.data(), static_cast<std::streamsize>(chunk.size()));
          chunk.clear();
        }
      };
      for (std::size_t i = 0; i < m.vertex_count(); ++i) {
        put(&m.points[3 * i], 12);
        put(&m.normals[3 * i], 12);
      }
      const unsigned char three = 3;
      for (std::size_t i = 0; i < m.triangle_count(); ++i) {
        put(&three, 1);
        put(&m.triangles[3 * i], 12);
      }
      os.write(chunk.data(), static_cast<std::streamsize>(chunk.size()));
    });
  }
};

}  // namespace

std::unique_ptr<Exporter> make_vdb_exporter(const std::filesystem::path& dir, const ExportOptions& options) {
  return std::make_unique<VdbExporter>(dir, options);
}
std::unique_ptr<Exporter> make_obj_exporter(const std::filesystem::path& dir, const ExportOptions& options) {
  return std::make_unique<ObjExporter>(dir, options);
}
std::unique_ptr<Exporter> make_ply_mesh_exporter(const std::filesystem::path& dir, const ExportOptions& options) {
  return std::make_unique<PlyMeshExporter>(dir, options);
}

}  // namespace rtsph::io
