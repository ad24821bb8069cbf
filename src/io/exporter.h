#pragma once
// Per-frame output in interchange formats, chosen by name: particles ("csv", "vtk", "ply") or
// the fluid's surface ("vdb" level set, "obj" and "ply-mesh" triangle meshes). Every exporter
// also keeps DIR/index.csv (frame,time_s,file) listing exactly the frames whose files
// are complete, rewritten atomically after each frame.
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/particles.h"
#include "io/errors.h"
#include "io/surface.h"

namespace rtsph::io {

/// Which per-particle attributes to write. Position is always written.
struct ExportOptions {
  bool velocity = true, density = true, pressure = true, id = true;
  /// Keep the frames already listed in DIR/index.csv (a run resumed from a checkpoint); frames
  /// at or after the first one written again are dropped from the index.
  bool resume = false;
  /// The surface formats' settings (spacing and dimension from the scene; the rest from flags).
  SurfaceOptions surface;
};

/// Parses an `--attributes` list such as "position,velocity,id" (order and repeats do not
/// matter, "all" selects everything). Throws std::invalid_argument naming the valid names.
ExportOptions parse_attributes(std::string_view list);
std::vector<std::string> attribute_names();

class Exporter {
 public:
  virtual ~Exporter() = default;
  /// Writes DIR/frame_NNNNNN.EXT, then updates the index. Particles are written in ascending
  /// id order so that frames compare row by row although the solver reorders memory each step.
  virtual void write_frame(int frame, double time_s, const ParticleView& view) = 0;
};

/// Creates `dir` if needed. Throws IoError for an unknown format (listing the valid ones) or
/// a directory that cannot be created, std::invalid_argument for surface options that format
/// cannot use (check_surface_options).
std::unique_ptr<Exporter> make_exporter(const std::string& format, const std::filesystem::path& dir,
                                        const ExportOptions& options = {});
std::vector<std::string> exporter_formats();
/// True for the formats that write the surface rather than the particles.
bool is_surface_format(std::string_view format);

}  // namespace rtsph::io
