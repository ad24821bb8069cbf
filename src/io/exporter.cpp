#include "io/exporter.h"

#include <stdexcept>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "io/atomic_file.h"
#include "io/formats.h"

namespace rtsph::io {
namespace {

struct ExporterEntry {
  std::string_view name;
  std::unique_ptr<Exporter> (*make)(const std::filesystem::path&, const ExportOptions&);
  bool surface;
};

constexpr ExporterEntry kExporters[] = {
    {"csv", make_csv_exporter, false},
    {"vtk", make_vtk_exporter, false},
    {"ply", make_ply_exporter, false},
    {"vdb", make_vdb_exporter, true},
    {"obj", make_obj_exporter, true},
    {"ply-mesh", make_ply_mesh_exporter, true},
};

constexpr std::string_view kAttributes[] = {"position", "velocity", "density", "pressure", "id"};

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

}  // namespace

std::vector<std::string> attribute_names() { return {std::begin(kAttributes), std::end(kAttributes)}; }

ExportOptions parse_attributes(std::string_view list) {
  ExportOptions o;
  o.velocity = o.density = o.pressure = o.id = false;
  while (true) {
    auto comma = list.find(',');
    auto name = trim(list.substr(0, comma));
    if (name == "all") {
      o.velocity = o.density = o.pressure = o.id = true;
    } else if (name == "velocity") {
      o.velocity = true;
    } else if (name == "density") {
      o.density = true;
    } else if (name == "pressure") {
      o.pressure = true;
    } else if (name == "id") {
      o.id = true;
    } else if (name != "position") {
      throw std::invalid_argument(fmt::format("unknown attribute '{}' (valid: {}, all)", name,
                                              fmt::join(kAttributes, ", ")));
    }
    if (comma == std::string_view::npos) break;
    list.remove_prefix(comma + 1);
  }
  return o;
}

std::vector<std::string> exporter_formats() {
  std::vector<std::string> names;
  for (const auto& e : kExporters) names.emplace_back(e.name);
  return names;
}

bool is_surface_format(std::string_view format) {
  for (const auto& e : kExporters)
    if (e.name == format) return e.surface;
  return false;
}

std::unique_ptr<Exporter> make_exporter(const std::string& format, const std::filesystem::path& dir,
                                        const ExportOptions& options) {
  for (const auto& e : kExporters) {
    if (e.name == format) {
      if (e.surface) check_surface_options(format, options.surface);
      ensure_directory(dir);
      return e.make(dir, options);
    }
  }
  // A bad argument, not an I/O failure: `rtsph run` exits 2 for it, as for an unknown attribute.
  throw std::invalid_argument(
      fmt::format("unknown output format '{}' (valid: {})", format, fmt::join(exporter_formats(), ", ")));
}

}  // namespace rtsph::io
