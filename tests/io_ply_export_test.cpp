// PLY exporter: an independent reader parses the header and the binary body; every value must
// match bit for bit, in id order.
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <random>
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

struct Ply {
  std::vector<std::string> comments;
  std::vector<std::pair<std::string, std::string>> properties;  // (type, name)
  std::size_t count = 0;
  std::string body;
  std::size_t record = 0;

  /// Raw 4-byte value of property `name` of vertex `i`.
  std::uint32_t bits(std::size_t i, const std::string& name) const {
    std::size_t off = 0;
    for (const auto& [type, prop] : properties) {
      if (prop == name) {
        std::uint32_t v;
        std::memcpy(&v, body.data() + i * record + off, 4);
        return v;
      }
      off += 4;
    }
    ADD_FAILURE() << "no property " << name;
    return 0;
  }
  float f(std::size_t i, const std::string& name) const { return std::bit_cast<float>(bits(i, name)); }
};

/// Reads binary little-endian PLY with one vertex element of 4-byte properties.
Ply parse_ply(const std::string& file) {
  Ply ply;
  const auto end = file.find("end_header\n");
  EXPECT_NE(end, std::string::npos);
  std::stringstream head(file.substr(0, end));
  std::string line;
  std::getline(head, line);
  EXPECT_EQ(line, "ply");
  std::getline(head, line);
  EXPECT_EQ(line, "format binary_little_endian 1.0");
  while (std::getline(head, line)) {
    std::stringstream words(line);
    std::string kw;
    words >> kw;
    if (kw == "comment") {
      ply.comments.push_back(line.substr(8));
    } else if (kw == "element") {
      std::string what;
      words >> what >> ply.count;
      EXPECT_EQ(what, "vertex");
    } else if (kw == "property") {
      std::string type, name;
      words >> type >> name;
      EXPECT_TRUE(type == "float" || type == "uint") << type;
      ply.properties.emplace_back(type, name);
    } else {
      ADD_FAILURE() << "unexpected header line " << line;
    }
  }
  ply.record = 4 * ply.properties.size();
  ply.body = file.substr(end + std::string("end_header\n").size());
  EXPECT_EQ(ply.body.size(), ply.count * ply.record);
  return ply;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

template <class T>
void append(std::string& s, T v) {
  s.append(reinterpret_cast<const char*>(&v), sizeof v);
}

TEST(PlyReader, ParsesHandWrittenReference) {
  std::string f = "ply\nformat binary_little_endian 1.0\ncomment hi\nelement vertex 2\n"
                  "property float x\nproperty uint id\nend_header\n";
  append(f, 1.25f), append<std::uint32_t>(f, 7);
  append(f, -0.5f), append<std::uint32_t>(f, 0xdeadbeef);
  auto ply = parse_ply(f);
  EXPECT_EQ(ply.comments, std::vector<std::string>{"hi"});
  ASSERT_EQ(ply.count, 2u);
  EXPECT_EQ(ply.f(0, "x"), 1.25f);
  EXPECT_EQ(ply.f(1, "x"), -0.5f);
  EXPECT_EQ(ply.bits(1, "id"), 0xdeadbeefu);
}

class PlyExportTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(::testing::TempDir()) /
           ("rtsph_ply_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
            std::to_string(::getpid()));
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

std::vector<std::string> names(const Ply& ply) {
  std::vector<std::string> out;
  for (const auto& [type, name] : ply.properties) out.push_back(type + " " + name);
  return out;
}

void check_round_trip(const fs::path& dir, int dim, std::uint32_t id_stride) {
  const std::size_t n = 311;
  Fluid f(dim, n, id_stride, 23 + dim);
  make_exporter("ply", dir)->write_frame(4, 0.5, f.view());
  auto ply = parse_ply(slurp(dir / "frame_000004.ply"));
  ASSERT_EQ(ply.count, n);
  ASSERT_EQ(names(ply), (std::vector<std::string>{"float x", "float y", "float z", "float vx", "float vy", "float vz",
                                                  "float density", "float pressure", "uint id"}));
  auto order = f.by_id();
  const char* axis[] = {"x", "y", "z"};
  for (std::size_t j = 0; j < n; ++j) {
    const auto i = order[j];
    const std::string at = "vertex " + std::to_string(j);
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(ply.bits(j, axis[k]), std::bit_cast<std::uint32_t>(k < dim ? f.x[k][i] : 0.0f)) << at;
      EXPECT_EQ(ply.bits(j, std::string("v") + axis[k]), std::bit_cast<std::uint32_t>(k < dim ? f.v[k][i] : 0.0f))
          << at;
    }
    EXPECT_EQ(ply.bits(j, "density"), std::bit_cast<std::uint32_t>(f.rho[i])) << at;
    EXPECT_EQ(ply.bits(j, "pressure"), std::bit_cast<std::uint32_t>(f.p[i])) << at;
    EXPECT_EQ(ply.bits(j, "id"), f.id[i]) << at;
  }
}

TEST_F(PlyExportTest, RoundTrips2DWithZeroZ) { check_round_trip(dir_, 2, 1); }
TEST_F(PlyExportTest, RoundTrips3DWithSparseIds) { check_round_trip(dir_, 3, 100'003); }

TEST_F(PlyExportTest, AttributeSelectionDropsProperties) {
  Fluid f(2, 40, 1, 9);
  make_exporter("ply", dir_, parse_attributes("density"))->write_frame(0, 0.0, f.view());
  auto ply = parse_ply(slurp(dir_ / "frame_000000.ply"));
  EXPECT_EQ(names(ply), (std::vector<std::string>{"float x", "float y", "float z", "float density"}));
  auto order = f.by_id();
  for (std::size_t j = 0; j < order.size(); ++j) {
    EXPECT_EQ(ply.bits(j, "density"), std::bit_cast<std::uint32_t>(f.rho[order[j]]));
  }
}

TEST_F(PlyExportTest, EmptyFrameAndIndex) {
  Fluid f(3, 0, 1, 9);
  auto ex = make_exporter("ply", dir_);
  ex->write_frame(0, 0.0, f.view());
  ex->write_frame(1, 1.5, f.view());
  auto ply = parse_ply(slurp(dir_ / "frame_000001.ply"));
  EXPECT_EQ(ply.count, 0u);
  EXPECT_EQ(ply.comments, std::vector<std::string>{"rtsph frame 1 time_s 1.5"});
  EXPECT_EQ(slurp(dir_ / "index.csv"), "frame,time_s,file\n0,0,frame_000000.ply\n1,1.5,frame_000001.ply\n");
}

}  // namespace
