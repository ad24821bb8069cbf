#pragma once
// The fluid's surface for other programs: a narrow-band level set built from the particles with
// OpenVDB, and a triangle mesh of it. OpenVDB is heavy to compile, so surface_vdb.cpp is the one
// file that includes it; this header shows none of its types.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string_view>
#include <vector>

#include "core/particles.h"

namespace rtsph::io {

struct SurfaceOptions {
  double spacing_m = 0;       // the scene's particle spacing (fluid.spacing); must be set
  double voxel_size_m = 0;    // level-set voxel edge; 0 = 0.4 × spacing (see voxel_size())
  double radius_factor = 1;   // each particle is a sphere of radius factor × spacing
  double adaptivity = 0;      // volume-to-mesh adaptivity: 0 uniform quads … 1 fewest polygons
  int dimension = 3;          // of the scene; surfaces are 3D only
  int threads = 0;            // OpenVDB's (TBB) worker threads; 0 = all cores

  /// The default, 0.4 spacing, is deliberately not a whole fraction of the spacing: with 1/2 the
  /// starting lattice falls on voxel centres or between them depending on where the block sits,
  /// and the block's measured volume varied from -0.5 % to -5 % with that alignment; at 0.4 it
  /// stays within -1 % for every offset tried (tests/io_surface_vdb_test.cpp).
  double voxel_size() const { return voxel_size_m > 0 ? voxel_size_m : 0.4 * spacing_m; }
  double radius() const { return radius_factor * spacing_m; }
};

/// Throws std::invalid_argument, one line naming the option and its value, when `format` cannot
/// be written with these options: a 2D scene, no spacing, a voxel too coarse for the particle
/// radius (under 1.5 voxels, OpenVDB drops the particle) or so fine it would take gigabytes,
/// a radius that leaves holes between lattice neighbours, adaptivity outside [0, 1].
void check_surface_options(std::string_view format, const SurfaceOptions& options);

struct SurfaceMesh {
  std::vector<float> points;              // x y z per vertex, m
  std::vector<float> normals;             // unit outward normal per vertex (level-set gradient)
  std::vector<std::uint32_t> triangles;   // 3 vertex indices each, counter-clockwise from outside
  std::size_t vertex_count() const { return points.size() / 3; }
  std::size_t triangle_count() const { return triangles.size() / 3; }
};

/// Flips the shared edge of each triangle that faces against its own vertices' normals (a fold)
/// with a neighbour, where the two new triangles both face outwards: the mesh stays closed and
/// consistently wound, and keeps its vertices. Adaptive meshing leaves such folds, mostly slivers
/// on flat faces (mesh_unfold.cpp). Returns the triangles that still face inwards.
std::size_t unfold_triangles(SurfaceMesh& mesh);

/// The fluid surface as a signed-distance narrow band (negative inside), built as OpenVDB's
/// particle fluid surface is: rasterise every particle as a sphere (tools::ParticlesToLevelSet),
/// smooth away the bumps between spheres (LevelSetFilter), then erode so that a flat face lies
/// half a spacing beyond the outermost particle centres, where the fluid's volume ends.
class FluidLevelSet {
 public:
  /// Particles with non-finite or absurd (beyond ±1e6 voxels) positions are skipped.
  FluidLevelSet(const ParticleView& view, const SurfaceOptions& options);
  ~FluidLevelSet();
  FluidLevelSet(const FluidLevelSet&) = delete;
  FluidLevelSet& operator=(const FluidLevelSet&) = delete;

  /// OpenVDB's volume-to-mesh at the zero crossing, quads split into triangles.
  SurfaceMesh mesh(double adaptivity) const;
  /// Writes grids "surface" (the level set) and "density" (a fog volume: 1 inside, falling to 0
  /// across the band) to `path` directly; callers make it atomic (write_file_atomic_via_path).
  void write_vdb(const std::filesystem::path& path, int frame, double time_s) const;
  std::size_t active_voxels() const;
  std::size_t skipped_particles() const { return skipped_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::size_t skipped_ = 0;
};

}  // namespace rtsph::io
