// Everything that touches OpenVDB (the only translation unit that includes it: its headers
// take long to compile, and CI builds twice on two cores).
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/GridOperators.h>
#include <openvdb/tools/Interpolation.h>
#include <openvdb/tools/LevelSetFilter.h>
#include <openvdb/tools/LevelSetUtil.h>
#include <openvdb/tools/ParticlesToLevelSet.h>
#include <openvdb/tools/VolumeToMesh.h>
#include <tbb/global_control.h>

#include "io/errors.h"
#include "io/surface.h"

namespace rtsph::io {
namespace {

using openvdb::FloatGrid;

/// The narrow band's half width in voxels: OpenVDB's default (3) plus room for the erosion.
constexpr double kHalfWidthVoxels = 4.0;
/// Voxel limits relative to the particle radius: OpenVDB ignores spheres under 1.5 voxels
/// (ParticlesToLevelSet's Rmin), and a radius of more than 24 voxels makes a surface of a
/// million particles cost gigabytes for no visible gain.
constexpr double kMinRadiusVoxels = 1.5, kMaxRadiusVoxels = 24.0;
/// In a cubic lattice, spheres of radius √3/2 spacing touch at the cell centres; smaller ones
/// leave holes (bubbles inside the fluid). Larger than 3 spacings smooths small drops away.
constexpr double kMinRadiusFactor = 0.9, kMaxRadiusFactor = 3.0;
/// Positions farther than this many voxels from the origin are skipped: OpenVDB's coordinates
/// are 32-bit, and one stray particle must not make the tree span the whole index space.
constexpr double kMaxCoordVoxels = 1e6;

/// ParticlesToLevelSet's particle list (see its header) over the finite, in-range particles.
struct ParticleList {
  using PosType = openvdb::Vec3R;  // PointPartitioner's requirement
  const ParticleView* view;
  std::vector<std::uint32_t> kept;
  std::size_t size() const { return kept.size(); }
  void getPos(std::size_t n, openvdb::Vec3R& xyz) const {
    const auto i = kept[n];
    xyz = openvdb::Vec3R(view->x[0][i], view->x[1][i], view->x[2][i]);
  }
};

/// Restricts OpenVDB's TBB workers to the run's thread count while one object is alive.
std::unique_ptr<tbb::global_control> limit_threads(int threads) {
  if (threads <= 0) return nullptr;
  return std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                               static_cast<std::size_t>(threads));
}

/// The mean height above the particle-centre plane of a flat face of spheres of radius r on a
/// square lattice of spacing s, averaged over one lattice cell: ⟨√(r² − d²)⟩ ≈ r − s²/(12 r)
/// (⟨d²⟩ = s²/6 over the cell; within 1 % of s for r ≥ 0.9 s). Smoothing moves the face to
/// this mean, so eroding by it minus s/2 puts the face half a spacing beyond the outer particle
/// centres: the boundary of the volume the particles stand for.
double erosion(double r, double s) { return r - s * s / (12.0 * r) - 0.5 * s; }

}  // namespace

struct FluidLevelSet::Impl {
  FloatGrid::Ptr grid;
};

void check_surface_options(std::string_view format, const SurfaceOptions& o) {
  if (o.dimension != 3) {
    throw std::invalid_argument(fmt::format("--format {}: surfaces are 3D only and the scene is {}D "
                                            "(use csv, vtk or ply for 2D particles)",
                                            format, o.dimension));
  }
  if (!(o.spacing_m > 0) || !std::isfinite(o.spacing_m)) {
    throw std::invalid_argument(fmt::format("--format {}: the particle spacing {} m is not positive", format, o.spacing_m));
  }
  if (!(o.radius_factor >= kMinRadiusFactor && o.radius_factor <= kMaxRadiusFactor)) {
    throw std::invalid_argument(fmt::format("--surface-radius {}: must be between {} and {} (× spacing)",
                                            o.radius_factor, kMinRadiusFactor, kMaxRadiusFactor));
  }
  const double voxel = o.voxel_size(), radius_voxels = o.radius() / voxel;
  if (!std::isfinite(voxel) || !(radius_voxels >= kMinRadiusVoxels && radius_voxels <= kMaxRadiusVoxels)) {
    throw std::invalid_argument(fmt::format(
        "--voxel-size {:g} m: must be between {:.4g} and {:.4g} m for a particle radius of {:g} m "
        "(spacing {:g} m × --surface-radius {:g}: {} to {} voxels)",
        voxel, o.radius() / kMaxRadiusVoxels, o.radius() / kMinRadiusVoxels, o.radius(), o.spacing_m,
        o.radius_factor, kMinRadiusVoxels, kMaxRadiusVoxels));
  }
  if (!(o.adaptivity >= 0 && o.adaptivity <= 1)) {
    throw std::invalid_argument(fmt::format("--adaptivity {}: must be between 0 and 1", o.adaptivity));
  }
}

FluidLevelSet::FluidLevelSet(const ParticleView& view, const SurfaceOptions& o) : impl_(std::make_unique<Impl>()) {
  check_surface_options("surface", o);
  if (view.dim != 3) throw std::invalid_argument(fmt::format("surface: the particles are {}D, not 3D", view.dim));
  openvdb::initialize();  // registers grid types for I/O; idempotent and thread-safe
  const auto threads = limit_threads(o.threads);
  const double voxel = o.voxel_size(), radius = o.radius(), limit = kMaxCoordVoxels * voxel;

  ParticleList list{&view, {}};
  list.kept.reserve(view.count);
  for (std::size_t i = 0; i < view.count; ++i) {
    bool ok = true;
    for (int k = 0; k < 3; ++k) ok = ok && std::abs(view.x[k][i]) < limit;  // false for NaN
    if (ok) list.kept.push_back(static_cast<std::uint32_t>(i));
  }
  skipped_ = view.count - list.kept.size();

  auto& grid = impl_->grid;
  grid = openvdb::createLevelSet<FloatGrid>(voxel, kHalfWidthVoxels);
  grid->setName("surface");
  if (!list.kept.empty()) {
    openvdb::tools::ParticlesToLevelSet<FloatGrid> raster(*grid);
    raster.rasterizeSpheres(list, radius);
    raster.finalize(/*prune=*/true);
    // Smoothing then erosion (Houdini's particle fluid surface does dilate-smooth-erode; the
    // sphere radius is the dilation). Three steps of mean-curvature flow flatten the bumps
    // between neighbouring spheres and leave flat faces where they are; of mean-value, Gaussian
    // and mean-curvature smoothing it kept a block's volume closest (-1 % worst vs -2 %).
    openvdb::tools::LevelSetFilter<FloatGrid> filter(*grid);
    for (int i = 0; i < 3; ++i) filter.meanCurvature();
    filter.offset(static_cast<float>(erosion(radius, o.spacing_m)));
  }
}

FluidLevelSet::~FluidLevelSet() = default;

std::size_t FluidLevelSet::active_voxels() const { return impl_->grid->activeVoxelCount(); }

SurfaceMesh FluidLevelSet::mesh(double adaptivity) const {
  std::vector<openvdb::Vec3s> points;
  std::vector<openvdb::Vec3I> triangles;
  std::vector<openvdb::Vec4I> quads;
  openvdb::tools::volumeToMesh(*impl_->grid, points, triangles, quads, 0.0, adaptivity);

  SurfaceMesh m;
  m.points.reserve(points.size() * 3);
  for (const auto& p : points) m.points.insert(m.points.end(), {p.x(), p.y(), p.z()});
  // OpenVDB winds its polygons clockwise seen from outside (normals into the negative
  // inside); reversed here so the usual right-hand rule gives outward normals.
  m.triangles.reserve(triangles.size() * 3 + quads.size() * 6);
  for (const auto& t : triangles) m.triangles.insert(m.triangles.end(), {t[2], t[1], t[0]});
  for (const auto& q : quads) m.triangles.insert(m.triangles.end(), {q[2], q[1], q[0], q[3], q[2], q[0]});

  // Vertex normals from the level set's gradient (central differences of the trilinear SDF,
  // half a voxel apart): smoother than face normals and independent of the triangulation.
  openvdb::tools::GridSampler<FloatGrid, openvdb::tools::BoxSampler> sdf(*impl_->grid);
  const double h = 0.5 * impl_->grid->voxelSize()[0];
  m.normals.reserve(m.points.size());
  for (const auto& p : points) {
    openvdb::Vec3d n;
    for (int k = 0; k < 3; ++k) {
      openvdb::Vec3d a(p), b(p);
      a[k] += h;
      b[k] -= h;
      n[k] = sdf.wsSample(a) - sdf.wsSample(b);
    }
    const double len = n.length();
    if (len > 0) n /= len;
    m.normals.insert(m.normals.end(), {float(n.x()), float(n.y()), float(n.z())});
  }
  unfold_triangles(m);
  return m;
}

void FluidLevelSet::write_vdb(const std::filesystem::path& path, int frame, double time_s) const {
  openvdb::GridPtrVec grids;
  grids.push_back(impl_->grid);
  FloatGrid::Ptr fog = impl_->grid->deepCopy();
  openvdb::tools::sdfToFogVolume(*fog);
  fog->setName("density");
  grids.push_back(fog);
  openvdb::MetaMap meta;
  meta.insertMeta("rtsph_frame", openvdb::Int32Metadata(frame));
  meta.insertMeta("rtsph_time_s", openvdb::DoubleMetadata(time_s));
  try {
    openvdb::io::File file(path.string());
    file.write(grids, meta);
    file.close();
  } catch (const openvdb::Exception& e) {
    throw IoError(fmt::format("cannot write '{}': {}", path.string(), e.what()));
  }
}

}  // namespace rtsph::io
