// VTK exporter: an independent reader parses the .vtp XML header and the raw appended block;
// every value must match bit for bit, in id order, and frames.pvd must list the frames.
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <numeric>
#include <random>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "io/exporter.h"
#include "io_test_fluid.h"

namespace fs = std::filesystem;
using namespace rtsph::io;

namespace {

using rtsph::test::Fluid;

struct VtpArray {
  std::string section, type;
  int components = 1;
  std::string bytes;
  template <class T>
  T at(std::size_t i) const {
    T v;
    EXPECT_LE((i + 1) * sizeof(T), bytes.size());
    std::memcpy(&v, bytes.data() + i * sizeof(T), sizeof(T));
    return v;
  }
};

struct Vtp {
  std::size_t points = 0, verts = 0;
  std::map<std::string, VtpArray> arrays;
};

std::map<std::string, std::string> attributes(const std::string& tag) {
  std::map<std::string, std::string> a;
  static const std::regex kAttr(R"re((\w+)="([^"]*)")re");
  for (std::sregex_iterator it(tag.begin(), tag.end(), kAttr), end; it != end; ++it) a[(*it)[1]] = (*it)[2];
  return a;
}

std::size_t type_size(const std::string& t) {
  if (t == "Float32" || t == "UInt32" || t == "Int32") return 4;
  if (t == "Int64" || t == "UInt64" || t == "Float64") return 8;
  ADD_FAILURE() << "unexpected type " << t;
  return 1;
}

/// Reads the subset of VTK XML PolyData that rtsph writes: raw appended, UInt64 headers.
Vtp parse_vtp(const std::string& file) {
  Vtp vtp;
  const std::string marker = "<AppendedData encoding=\"raw\">";
  const auto app = file.find(marker);
  EXPECT_NE(app, std::string::npos);
  const auto base = file.find('_', app + marker.size()) + 1;
  const std::string xml = file.substr(0, app);

  static const std::regex kTag(R"re(<(/?)(\w+)([^>]*)>)re");
  std::string section;
  std::size_t end_of_data = base;
  for (std::sregex_iterator it(xml.begin(), xml.end(), kTag), end; it != end; ++it) {
    const std::string closing = (*it)[1], name = (*it)[2], rest = (*it)[3];
    auto a = attributes(rest);
    if (name == "VTKFile" && closing.empty()) {
      EXPECT_EQ(a["type"], "PolyData");
      EXPECT_EQ(a["byte_order"], "LittleEndian");
      EXPECT_EQ(a["header_type"], "UInt64");
    } else if (name == "Piece" && closing.empty()) {
      vtp.points = std::stoul(a["NumberOfPoints"]);
      vtp.verts = std::stoul(a["NumberOfVerts"]);
    } else if (name == "PointData" || name == "Points" || name == "Verts" || name == "CellData") {
      section = closing.empty() ? name : "";
    } else if (name == "DataArray") {
      EXPECT_EQ(a["format"], "appended");
      VtpArray arr;
      arr.section = section;
      arr.type = a["type"];
      if (a.count("NumberOfComponents")) arr.components = std::stoi(a["NumberOfComponents"]);
      const auto at = base + std::stoul(a["offset"]);
      std::uint64_t n = 0;
      std::memcpy(&n, file.data() + at, 8);
      EXPECT_LE(at + 8 + n, file.size());
      arr.bytes = file.substr(at + 8, n);
      end_of_data = std::max<std::size_t>(end_of_data, at + 8 + n);
      const std::size_t count = section == "Verts" ? vtp.verts : vtp.points;
      EXPECT_EQ(n, count * arr.components * type_size(arr.type)) << a["Name"];
      vtp.arrays[a["Name"]] = arr;
    }
  }
  const auto tail = file.substr(end_of_data);
  EXPECT_NE(tail.find("</AppendedData>"), std::string::npos);
  EXPECT_NE(tail.find("</VTKFile>"), std::string::npos);
  return vtp;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void expect_bits(float got, float want, const std::string& what) {
  EXPECT_EQ(std::bit_cast<std::uint32_t>(got), std::bit_cast<std::uint32_t>(want)) << what;
}

template <class T>
void append(std::string& s, T v) {
  s.append(reinterpret_cast<const char*>(&v), sizeof v);
}

TEST(VtpReader, ParsesHandWrittenReference) {
  std::string f =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
      "<PolyData><Piece NumberOfPoints=\"2\" NumberOfVerts=\"2\">\n"
      "<PointData><DataArray type=\"Float32\" Name=\"density\" format=\"appended\" offset=\"0\"/></PointData>\n"
      "<Points><DataArray type=\"Float32\" Name=\"Points\" NumberOfComponents=\"3\" format=\"appended\" "
      "offset=\"16\"/></Points>\n"
      "</Piece></PolyData>\n<AppendedData encoding=\"raw\">\n_";
  append<std::uint64_t>(f, 8);
  append(f, 1000.5f), append(f, -3.0f);
  append<std::uint64_t>(f, 24);
  for (float c : {1.f, 2.f, 3.f, 4.f, 5.f, 6.f}) append(f, c);
  f += "\n</AppendedData>\n</VTKFile>\n";
  auto vtp = parse_vtp(f);
  EXPECT_EQ(vtp.points, 2u);
  ASSERT_EQ(vtp.arrays.size(), 2u);
  EXPECT_EQ(vtp.arrays["density"].section, "PointData");
  EXPECT_EQ(vtp.arrays["density"].at<float>(1), -3.0f);
  EXPECT_EQ(vtp.arrays["Points"].section, "Points");
  EXPECT_EQ(vtp.arrays["Points"].components, 3);
  EXPECT_EQ(vtp.arrays["Points"].at<float>(4), 5.0f);
}

class VtkExportTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(::testing::TempDir()) /
           ("rtsph_vtk_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
            std::to_string(::getpid()));
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

void check_round_trip(const fs::path& dir, int dim, std::uint32_t id_stride) {
  const std::size_t n = 257;
  Fluid f(dim, n, id_stride, 11 + dim);
  make_exporter("vtk", dir)->write_frame(0, 0.0, f.view());
  auto vtp = parse_vtp(slurp(dir / "frame_000000.vtp"));
  ASSERT_EQ(vtp.points, n);
  ASSERT_EQ(vtp.verts, n);
  for (const char* name : {"Points", "velocity", "density", "pressure", "id", "connectivity", "offsets"}) {
    ASSERT_TRUE(vtp.arrays.count(name)) << name;
  }
  const auto& pts = vtp.arrays["Points"];
  const auto& vel = vtp.arrays["velocity"];
  EXPECT_EQ(pts.section, "Points");
  EXPECT_EQ(pts.type, "Float32");
  EXPECT_EQ(pts.components, 3);
  EXPECT_EQ(vel.section, "PointData");
  EXPECT_EQ(vel.components, 3);
  EXPECT_EQ(vtp.arrays["id"].type, "UInt32");
  EXPECT_EQ(vtp.arrays["connectivity"].section, "Verts");
  EXPECT_EQ(vtp.arrays["offsets"].type, "Int32");
  auto order = f.by_id();
  for (std::size_t j = 0; j < n; ++j) {
    const auto i = order[j];
    const std::string at = "point " + std::to_string(j);
    for (int k = 0; k < 3; ++k) {
      expect_bits(pts.at<float>(3 * j + k), k < dim ? f.x[k][i] : 0.0f, at + " x");
      expect_bits(vel.at<float>(3 * j + k), k < dim ? f.v[k][i] : 0.0f, at + " v");
    }
    expect_bits(vtp.arrays["density"].at<float>(j), f.rho[i], at + " density");
    expect_bits(vtp.arrays["pressure"].at<float>(j), f.p[i], at + " pressure");
    EXPECT_EQ(vtp.arrays["id"].at<std::uint32_t>(j), f.id[i]) << at;
    EXPECT_EQ(vtp.arrays["connectivity"].at<std::int32_t>(j), static_cast<std::int32_t>(j));
    EXPECT_EQ(vtp.arrays["offsets"].at<std::int32_t>(j), static_cast<std::int32_t>(j + 1));
  }
}

TEST_F(VtkExportTest, RoundTrips2DWithZeroZ) { check_round_trip(dir_, 2, 1); }
TEST_F(VtkExportTest, RoundTrips3DWithSparseIds) { check_round_trip(dir_, 3, 100'003); }

TEST_F(VtkExportTest, AttributeSelectionDropsArrays) {
  Fluid f(3, 30, 1, 5);
  make_exporter("vtk", dir_, parse_attributes("position,id"))->write_frame(0, 0.0, f.view());
  auto vtp = parse_vtp(slurp(dir_ / "frame_000000.vtp"));
  std::vector<std::string> names;
  for (const auto& [name, arr] : vtp.arrays) names.push_back(name);
  EXPECT_EQ(names, (std::vector<std::string>{"Points", "connectivity", "id", "offsets"}));
}

TEST_F(VtkExportTest, EmptyFrameIsValid) {
  Fluid f(3, 0, 1, 5);
  make_exporter("vtk", dir_)->write_frame(0, 0.0, f.view());
  auto vtp = parse_vtp(slurp(dir_ / "frame_000000.vtp"));
  EXPECT_EQ(vtp.points, 0u);
  EXPECT_EQ(vtp.arrays.size(), 7u);
}

TEST_F(VtkExportTest, PvdAndIndexListTheFrames) {
  Fluid f(2, 10, 1, 3);
  auto ex = make_exporter("vtk", dir_);
  ex->write_frame(0, 0.0, f.view());
  ex->write_frame(1, 0.125, f.view());
  EXPECT_EQ(slurp(dir_ / "frames.pvd"),
            "<?xml version=\"1.0\"?>\n"
            "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
            "  <Collection>\n"
            "    <DataSet timestep=\"0\" group=\"\" part=\"0\" file=\"frame_000000.vtp\"/>\n"
            "    <DataSet timestep=\"0.125\" group=\"\" part=\"0\" file=\"frame_000001.vtp\"/>\n"
            "  </Collection>\n"
            "</VTKFile>\n");
  EXPECT_EQ(slurp(dir_ / "index.csv"), "frame,time_s,file\n0,0,frame_000000.vtp\n1,0.125,frame_000001.vtp\n");
}

}  // namespace
