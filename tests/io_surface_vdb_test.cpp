// Surface formats (issue 11 §5-6): the level set of a resting cubic block, written with
// `--format vdb`, opens with OpenVDB's own reader and passes its level-set diagnostics; the mesh
// (`obj`, `ply-mesh`) is closed, consistently wound with outward normals, encloses the block's
// volume within 5 % and spans its bounding box within one spacing. The block is a WCSPH tank
// (4096 particles) at rest: the starting lattice, and the state after 0.1 s of settling.
// This file and src/io/surface_vdb.cpp are the only ones that include OpenVDB.
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Diagnostics.h>
#include <openvdb/tools/Interpolation.h>
#include <openvdb/tools/LevelSetMeasure.h>

#include "io/exporter.h"
#include "io/frame_index.h"
#include "io/surface.h"
#include "solvers/simulation.h"
#include "test_scenes.h"

namespace fs = std::filesystem;
using namespace rtsph;
using namespace rtsph::io;

namespace {

constexpr double kSpacing = 0.02, kSide = 16 * kSpacing;  // 16³ particles

/// Vertices and triangles read back from a written file.
struct Mesh {
  std::vector<std::array<double, 3>> v, n;
  std::vector<std::array<std::uint32_t, 3>> f;
};

Mesh read_obj(const fs::path& file) {
  Mesh m;
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream s(line);
    std::string tag;
    s >> tag;
    if (tag == "v" || tag == "vn") {
      std::array<double, 3> a{};
      s >> a[0] >> a[1] >> a[2];
      (tag == "v" ? m.v : m.n).push_back(a);
    } else if (tag == "f") {
      std::array<std::uint32_t, 3> t{};
      for (auto& k : t) {
        std::string corner;
        s >> corner;  // "a//a": vertex and normal index agree
        const auto slash = corner.find("//");
        EXPECT_EQ(corner.substr(0, slash), corner.substr(slash + 2)) << corner;
        k = static_cast<std::uint32_t>(std::stoul(corner.substr(0, slash)) - 1);
      }
      m.f.push_back(t);
    }
  }
  return m;
}

Mesh read_ply_mesh(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::string line;
  std::size_t nv = 0, nf = 0;
  while (std::getline(in, line) && line != "end_header") {
    std::sscanf(line.c_str(), "element vertex %zu", &nv);
    std::sscanf(line.c_str(), "element face %zu", &nf);
  }
  Mesh m;
  for (std::size_t i = 0; i < nv; ++i) {
    float r[6];
    in.read(reinterpret_cast<char*>(r), sizeof r);
    m.v.push_back({r[0], r[1], r[2]});
    m.n.push_back({r[3], r[4], r[5]});
  }
  for (std::size_t i = 0; i < nf; ++i) {
    unsigned char count = 0;
    std::uint32_t t[3];
    in.read(reinterpret_cast<char*>(&count), 1);
    EXPECT_EQ(count, 3);
    in.read(reinterpret_cast<char*>(t), sizeof t);
    m.f.push_back({t[0], t[1], t[2]});
  }
  EXPECT_TRUE(in.good()) << file;
  EXPECT_EQ(in.peek(), EOF) << file << ": bytes after the faces";
  return m;
}

using V3 = std::array<double, 3>;
V3 sub(const V3& a, const V3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
V3 cross(const V3& a, const V3& b) { return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; }
double dot(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/// Closed (every edge in exactly two triangles), consistently wound (the two run the edge in
/// opposite directions), no degenerate indices, normals unit and on the outer side of every
/// triangle they belong to. Returns the enclosed volume (divergence theorem) and the bounding box.
struct MeshCheck {
  double volume = 0;
  V3 lo{1e30, 1e30, 1e30}, hi{-1e30, -1e30, -1e30};
};
MeshCheck check_mesh(const Mesh& m) {
  MeshCheck c;
  EXPECT_GT(m.f.size(), 100u);
  EXPECT_EQ(m.n.size(), m.v.size());
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  std::size_t bad_normals = 0, bad_index = 0;
  for (const auto& t : m.f) {
    if (t[0] >= m.v.size() || t[1] >= m.v.size() || t[2] >= m.v.size() || t[0] == t[1] || t[1] == t[2] ||
        t[0] == t[2]) {
      ++bad_index;
      continue;
    }
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
    const V3 &a = m.v[t[0]], &b = m.v[t[1]], &d = m.v[t[2]];
    const V3 fn = cross(sub(b, a), sub(d, a));
    c.volume += dot(a, cross(b, d)) / 6.0;
    for (auto k : t) {
      if (!(dot(fn, m.n[k]) > 0) || std::abs(std::sqrt(dot(m.n[k], m.n[k])) - 1) > 1e-3) ++bad_normals;
    }
  }
  EXPECT_EQ(bad_index, 0u) << "triangles with out-of-range or repeated vertices";
  std::size_t open = 0, misoriented = 0;
  for (const auto& [e, count] : directed) {
    if (count > 1) ++misoriented;  // two triangles run this edge the same way
    if (!directed.count({e.second, e.first})) ++open;
  }
  EXPECT_EQ(open, 0u) << "edges with one triangle only (a hole)";
  EXPECT_EQ(misoriented, 0u) << "edges run twice in the same direction (winding flips)";
  EXPECT_EQ(bad_normals, 0u) << "vertex normals not unit or pointing into a triangle's back";
  for (const auto& p : m.v)
    for (int k = 0; k < 3; ++k) c.lo[k] = std::min(c.lo[k], p[k]), c.hi[k] = std::max(c.hi[k], p[k]);
  return c;
}

class SurfaceTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { openvdb::initialize(); }
  void SetUp() override {
    dir_ = fs::path(::testing::TempDir()) /
           ("rtsph_surface_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
            std::to_string(::getpid()));
    fs::remove_all(dir_);
    // The tank's fluid is the cube [0, L]³ (L = 16 spacings) in a container L wide and 1.5 L high.
    spec_ = test::tank(3, kSide, kSide, kSpacing);
    sim_ = make_simulation(spec_, 2);
  }
  void TearDown() override { fs::remove_all(dir_); }

  ExportOptions options(double adaptivity = 0) const {
    ExportOptions o;
    o.surface.spacing_m = kSpacing;
    o.surface.dimension = 3;
    o.surface.adaptivity = adaptivity;
    return o;
  }
  /// Writes one frame in `format` and returns its path.
  fs::path export_frame(const std::string& format, const ExportOptions& o) {
    const fs::path d = dir_ / format;
    make_exporter(format, d, o)->write_frame(0, sim_->time(), sim_->fluid());
    const auto index = read_index(d / "index.csv");
    EXPECT_EQ(index.size(), 1u);
    return d / index.at(0).file;
  }
  /// The mesh of the current state meets every property; returns the volume error.
  void check_block_mesh(const Mesh& m, const char* what) {
    const MeshCheck c = check_mesh(m);
    const double volume = kSide * kSide * kSide, error = c.volume / volume - 1;
    EXPECT_LT(std::abs(error), 0.05) << what << ": volume " << c.volume << " m³ vs block " << volume;
    const V3 lo{0, 0, 0}, hi{kSide, kSide, kSide};
    double worst = 0;
    for (int k = 0; k < 3; ++k) worst = std::max({worst, std::abs(c.lo[k] - lo[k]), std::abs(c.hi[k] - hi[k])});
    EXPECT_LT(worst, kSpacing) << what << ": bounding box [" << c.lo[0] << " " << c.lo[1] << " " << c.lo[2] << "] - ["
                               << c.hi[0] << " " << c.hi[1] << " " << c.hi[2] << "]";
    std::printf("%s at t = %.3g s: %zu vertices, %zu triangles, volume %.6g m³ (block %.6g, %+.2f %%), "
                "bounding box off by at most %.3g spacing\n",
                what, sim_->time(), m.v.size(), m.f.size(), c.volume, volume, 100 * error, worst / kSpacing);
  }
  void settle() {
    while (sim_->time() < 0.1) sim_->step();
  }

  fs::path dir_;
  SimSpec spec_;
  std::unique_ptr<Simulation> sim_;
};

/// Reads the file with OpenVDB's io::File and checks the level set (volume, extent, validity).
void check_vdb_file(const fs::path& file, double time_s) {
  openvdb::io::File f(file.string());
  ASSERT_NO_THROW(f.open()) << file;
  const auto meta = f.getMetadata();
  EXPECT_EQ(meta->metaValue<int>("rtsph_frame"), 0);
  EXPECT_EQ(meta->metaValue<double>("rtsph_time_s"), time_s);
  auto surface = openvdb::gridPtrCast<openvdb::FloatGrid>(f.readGrid("surface"));
  auto density = openvdb::gridPtrCast<openvdb::FloatGrid>(f.readGrid("density"));
  f.close();
  ASSERT_TRUE(surface && density) << "grids 'surface' and 'density' of type float";
  EXPECT_EQ(surface->getGridClass(), openvdb::GRID_LEVEL_SET);
  EXPECT_EQ(density->getGridClass(), openvdb::GRID_FOG_VOLUME);
  EXPECT_DOUBLE_EQ(surface->voxelSize()[0], 0.4 * kSpacing);
  // OpenVDB's own checks: a uniform linear transform, a narrow band of the right width, finite
  // values, the inside marked by the negative background.
  EXPECT_EQ(openvdb::tools::checkLevelSet(*surface, 7), "") << file;

  const double volume = openvdb::tools::levelSetVolume(*surface), block = kSide * kSide * kSide;
  EXPECT_LT(std::abs(volume / block - 1), 0.05) << "level-set volume " << volume << " m³ vs block " << block;
  // The zero crossing along the axes through the centre: each face within a spacing.
  openvdb::tools::GridSampler<openvdb::FloatGrid, openvdb::tools::BoxSampler> phi(*surface);
  const double c = 0.5 * kSide;
  EXPECT_LT(phi.wsSample(openvdb::Vec3d(c, c, c)), 0);
  EXPECT_EQ(density->tree().getValue(density->transform().worldToIndexCellCentered(openvdb::Vec3d(c, c, c))), 1.0f);
  double worst = 0;
  for (int k = 0; k < 3; ++k) {
    for (int side = 0; side < 2; ++side) {
      openvdb::Vec3d p(c, c, c);
      const double step = (side ? 1 : -1) * 1e-4;
      while (phi.wsSample(p) < 0 && std::abs(p[k] - c) < kSide) p[k] += step;
      worst = std::max(worst, std::abs(p[k] - (side ? kSide : 0.0)));
    }
  }
  EXPECT_LT(worst, kSpacing) << "a face of the level set is more than a spacing from the block's";
  std::printf("%s: level-set volume %.6g m³ (block %.6g, %+.2f %%), faces within %.3g spacing, %zu active "
              "voxels, %ju bytes\n",
              file.filename().c_str(), volume, block, 100 * (volume / block - 1), worst / kSpacing,
              std::size_t(surface->activeVoxelCount()), std::uintmax_t(fs::file_size(file)));
}

TEST_F(SurfaceTest, LevelSetOfTheRestingBlockReadsBackWithOpenVdb) {
  check_vdb_file(export_frame("vdb", options()), sim_->time());
  settle();
  fs::remove_all(dir_);
  check_vdb_file(export_frame("vdb", options()), sim_->time());
  for (const auto& e : fs::directory_iterator(dir_ / "vdb"))
    EXPECT_NE(e.path().filename().string()[0], '.') << "temporary file left: " << e.path();
}

TEST_F(SurfaceTest, MeshOfTheRestingBlockIsClosedAndMatchesTheBlock) {
  check_block_mesh(read_obj(export_frame("obj", options())), "obj (lattice)");
  settle();
  fs::remove_all(dir_);
  check_block_mesh(read_obj(export_frame("obj", options())), "obj (settled)");
  check_block_mesh(read_obj(export_frame("obj", options(0.5))), "obj adaptivity 0.5 (settled)");
}

/// An octahedron (vertex normals = positions), wound counter-clockwise from outside; `folded`
/// replaces its edge (+x, +y) by the diagonal (+z, -z) through the inside, so the two triangles
/// on that diagonal face sideways, against their vertices' normals.
SurfaceMesh octahedron(bool folded) {
  SurfaceMesh m;
  m.points = {1, 0, 0, 0, 1, 0, 0, 0, 1, -1, 0, 0, 0, -1, 0, 0, 0, -1};  // +x +y +z -x -y -z
  m.normals = m.points;
  m.triangles = {0, 1, 2, 1, 3, 2, 3, 4, 2, 4, 0, 2, 1, 0, 5, 3, 1, 5, 4, 3, 5, 0, 4, 5};
  if (folded) {  // (+x, +y, +z) and (+y, +x, -z) across (+x, +y) become (+x, -z, +z), (-z, +y, +z)
    const std::uint32_t a[] = {0, 5, 2}, b[] = {5, 1, 2};
    std::copy(a, a + 3, m.triangles.begin());
    std::copy(b, b + 3, m.triangles.begin() + 12);
  }
  return m;
}

std::size_t inward(const SurfaceMesh& m) {
  std::size_t count = 0;
  for (std::size_t t = 0; t < m.triangle_count(); ++t) {
    const std::uint32_t* v = &m.triangles[3 * t];
    auto p = [&](int k) { return V3{m.points[3 * v[k]], m.points[3 * v[k] + 1], m.points[3 * v[k] + 2]}; };
    const V3 fn = cross(sub(p(1), p(0)), sub(p(2), p(0)));
    for (int k = 0; k < 3; ++k)
      if (!(dot(fn, V3{m.normals[3 * v[k]], m.normals[3 * v[k] + 1], m.normals[3 * v[k] + 2]}) > 0)) {
        ++count;
        break;
      }
  }
  return count;
}

TEST(MeshUnfold, AFoldIsFlippedBackAndTheMeshStaysClosed) {
  SurfaceMesh m = octahedron(true);
  ASSERT_EQ(inward(m), 2u);
  EXPECT_EQ(unfold_triangles(m), 0u);
  EXPECT_EQ(inward(m), 0u);
  EXPECT_EQ(m.vertex_count(), 6u);
  // Closed and consistently wound: every directed edge once, and its reverse present.
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  for (std::size_t t = 0; t < m.triangle_count(); ++t)
    for (int k = 0; k < 3; ++k) ++directed[{m.triangles[3 * t + k], m.triangles[3 * t + (k + 1) % 3]}];
  EXPECT_EQ(directed.size(), 24u);
  for (const auto& [e, n] : directed) {
    EXPECT_EQ(n, 1);
    EXPECT_TRUE(directed.count({e.second, e.first}));
  }
  // The flip restored the edge (+x, +y) and removed the diagonal through the inside.
  EXPECT_TRUE(directed.count({0, 1}) || directed.count({1, 0}));
  EXPECT_FALSE(directed.count({2, 5}) || directed.count({5, 2}));
}

TEST(MeshUnfold, AMeshWithoutFoldsIsLeftAsItIs) {
  SurfaceMesh m = octahedron(false);
  const auto before = m.triangles;
  EXPECT_EQ(unfold_triangles(m), 0u);
  EXPECT_EQ(m.triangles, before);
}

TEST_F(SurfaceTest, PlyMeshHoldsTheSameMeshAsObj) {
  settle();
  const Mesh obj = read_obj(export_frame("obj", options())), ply = read_ply_mesh(export_frame("ply-mesh", options()));
  check_block_mesh(ply, "ply-mesh (settled)");
  ASSERT_EQ(obj.v.size(), ply.v.size());
  ASSERT_EQ(obj.f, ply.f);
  for (std::size_t i = 0; i < obj.v.size(); ++i) {
    for (int k = 0; k < 3; ++k) {  // the OBJ's shortest float text reads back as the same float
      ASSERT_EQ(float(obj.v[i][k]), float(ply.v[i][k])) << i;
      ASSERT_EQ(float(obj.n[i][k]), float(ply.n[i][k])) << i;
    }
  }
}

TEST_F(SurfaceTest, AdaptivityReducesTriangles) {
  const SurfaceOptions o = options().surface;
  const FluidLevelSet surface(sim_->fluid(), o);
  const auto uniform = surface.mesh(0).triangle_count(), adaptive = surface.mesh(1).triangle_count();
  std::printf("triangles: %zu at adaptivity 0, %zu at 1\n", uniform, adaptive);
  EXPECT_LT(adaptive, uniform / 2) << "a block's flat faces should merge into large polygons";
}

TEST_F(SurfaceTest, StrayParticlesAreSkippedNotFatal) {
  // A NaN and a far-away particle (beyond OpenVDB's coordinate range at this voxel size).
  std::vector<float> x{0.1f, NAN, 1e30f}, y{0.1f, 0.1f, 0.1f}, z{0.1f, 0.1f, 0.1f};
  ParticleView v;
  v.dim = 3;
  v.count = 3;
  v.x[0] = x.data(), v.x[1] = y.data(), v.x[2] = z.data();
  const FluidLevelSet surface(v, options().surface);
  EXPECT_EQ(surface.skipped_particles(), 2u);
  EXPECT_GT(surface.mesh(0).triangle_count(), 0u);  // the one good particle is a small drop
}

TEST(SurfaceOptionsTest, RefusalsNameTheOptionAndValue) {
  auto refused = [](const std::string& format, SurfaceOptions o) -> std::string {
    try {
      check_surface_options(format, o);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  SurfaceOptions ok;
  ok.spacing_m = 0.02;
  EXPECT_EQ(refused("vdb", ok), "");
  SurfaceOptions o = ok;
  o.dimension = 2;
  EXPECT_EQ(refused("obj", o), "--format obj: surfaces are 3D only and the scene is 2D (use csv, vtk or ply for 2D particles)");
  o = ok;
  o.voxel_size_m = 0.05;
  EXPECT_NE(refused("vdb", o).find("--voxel-size 0.05 m: must be between"), std::string::npos) << refused("vdb", o);
  o.voxel_size_m = 1e-5;
  EXPECT_NE(refused("vdb", o).find("--voxel-size 1e-05 m"), std::string::npos) << refused("vdb", o);
  o = ok;
  o.radius_factor = 0.5;
  EXPECT_NE(refused("vdb", o).find("--surface-radius 0.5"), std::string::npos);
  o = ok;
  o.adaptivity = 1.5;
  EXPECT_NE(refused("vdb", o).find("--adaptivity 1.5"), std::string::npos);
  // make_exporter applies the same checks before creating anything.
  ExportOptions eo;
  eo.surface = ok;
  eo.surface.dimension = 2;
  const fs::path d = fs::path(::testing::TempDir()) / ("rtsph_surface_refused_" + std::to_string(::getpid()));
  EXPECT_THROW(make_exporter("vdb", d, eo), std::invalid_argument);
  EXPECT_FALSE(fs::exists(d));
  for (const auto* f : {"vdb", "obj", "ply-mesh"}) EXPECT_TRUE(is_surface_format(f)) << f;
  for (const auto* f : {"csv", "vtk", "ply", "xyz"}) EXPECT_FALSE(is_surface_format(f)) << f;
}

}  // namespace
