#pragma once
// Factories of the built-in exporters, one per *_exporter.cpp; exporter.cpp lists them by name.
#include <filesystem>
#include <memory>

#include "io/exporter.h"

namespace rtsph::io {

std::unique_ptr<Exporter> make_csv_exporter(const std::filesystem::path& dir, const ExportOptions& options);
std::unique_ptr<Exporter> make_vtk_exporter(const std::filesystem::path& dir, const ExportOptions& options);
std::unique_ptr<Exporter> make_ply_exporter(const std::filesystem::path& dir, const ExportOptions& options);
// surface_exporter.cpp
std::unique_ptr<Exporter> make_vdb_exporter(const std::filesystem::path& dir, const ExportOptions& options);
std::unique_ptr<Exporter> make_obj_exporter(const std::filesystem::path& dir, const ExportOptions& options);
std::unique_ptr<Exporter> make_ply_mesh_exporter(const std::filesystem::path& dir, const ExportOptions& options);

}  // namespace rtsph::io
