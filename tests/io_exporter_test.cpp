// The exporter registry, --attributes parsing and index.csv behaviour shared by all formats.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "io/exporter.h"
#include "io/frame_index.h"

namespace fs = std::filesystem;
using namespace rtsph::io;

namespace {

class ExporterTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(::testing::TempDir()) /
           ("rtsph_exp_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
            std::to_string(::getpid()));
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  static std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  fs::path dir_;
};

/// Three particles in 2D; enough for index behaviour.
struct Tiny {
  float x[3] = {0, 1, 2}, y[3] = {3, 4, 5}, rho[3] = {1000, 1001, 999}, p[3] = {0, 1, 2};
  std::uint32_t id[3] = {2, 0, 1};
  rtsph::ParticleView view() const {
    rtsph::ParticleView w;
    w.dim = 2;
    w.count = 3;
    w.x[0] = w.v[0] = x;
    w.x[1] = w.v[1] = y;
    w.density = rho;
    w.pressure = p;
    w.id = id;
    return w;
  }
};

TEST(ExporterRegistry, ListsFormats) {
  EXPECT_EQ(exporter_formats(), (std::vector<std::string>{"csv", "vtk", "ply", "vdb", "obj", "ply-mesh"}));
}

TEST_F(ExporterTest, UnknownFormatNamesTheValidOnes) {
  try {
    make_exporter("xyz", dir_);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "unknown output format 'xyz' (valid: csv, vtk, ply, vdb, obj, ply-mesh)");
  }
}

TEST_F(ExporterTest, CreatesTheOutputDirectory) {
  make_exporter("csv", dir_ / "a" / "b");
  EXPECT_TRUE(fs::is_directory(dir_ / "a" / "b"));
}

TEST_F(ExporterTest, UncreatableDirectoryThrowsIoError) {
  fs::create_directories(dir_);
  std::ofstream(dir_ / "file") << "x";
  EXPECT_THROW(make_exporter("vtk", dir_ / "file" / "out"), IoError);
}

TEST(Attributes, ParsesLists) {
  auto all = parse_attributes("all");
  EXPECT_TRUE(all.velocity && all.density && all.pressure && all.id);
  auto some = parse_attributes(" position , id,density");
  EXPECT_FALSE(some.velocity);
  EXPECT_TRUE(some.density);
  EXPECT_FALSE(some.pressure);
  EXPECT_TRUE(some.id);
  auto pos = parse_attributes("position");
  EXPECT_FALSE(pos.velocity || pos.density || pos.pressure || pos.id);
  ExportOptions def;
  EXPECT_TRUE(def.velocity && def.density && def.pressure && def.id);
  EXPECT_EQ(attribute_names(), (std::vector<std::string>{"position", "velocity", "density", "pressure", "id"}));
}

TEST(Attributes, UnknownNameListsValidOnes) {
  try {
    parse_attributes("position,temperature");
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "unknown attribute 'temperature' (valid: position, velocity, density, pressure, id, all)");
  }
}

TEST_F(ExporterTest, MissingArrayIsRejected) {
  Tiny t;
  auto v = t.view();
  v.pressure = nullptr;
  auto ex = make_exporter("ply", dir_);
  EXPECT_THROW(ex->write_frame(0, 0, v), std::invalid_argument);
  // Not selected, so not needed.
  make_exporter("ply", dir_, parse_attributes("position,density,id,velocity"))->write_frame(0, 0, v);
  EXPECT_TRUE(fs::exists(dir_ / "frame_000000.ply"));
}

TEST_F(ExporterTest, FreshRunStartsANewIndex) {
  Tiny t;
  make_exporter("csv", dir_)->write_frame(0, 0.0, t.view());
  make_exporter("csv", dir_)->write_frame(5, 0.5, t.view());
  EXPECT_EQ(slurp(dir_ / "index.csv"), "frame,time_s,file\n5,0.5,frame_000005.csv\n");
}

TEST_F(ExporterTest, ResumedRunKeepsEarlierFramesAndDropsLaterOnes) {
  Tiny t;
  {
    auto ex = make_exporter("vtk", dir_);
    for (int f = 0; f < 4; ++f) ex->write_frame(f, f * 0.1, t.view());
  }
  ExportOptions o;
  o.resume = true;
  make_exporter("vtk", dir_, o)->write_frame(2, 0.2, t.view());
  auto idx = read_index(dir_ / "index.csv");
  ASSERT_EQ(idx.size(), 3u);
  EXPECT_EQ(idx[2].frame, 2);
  EXPECT_EQ(idx[2].file, "frame_000002.vtp");
  EXPECT_DOUBLE_EQ(idx[1].time_s, 0.1);
  EXPECT_EQ(slurp(dir_ / "frames.pvd").find("frame_000003"), std::string::npos);
  EXPECT_NE(slurp(dir_ / "frames.pvd").find("frame_000001"), std::string::npos);
}

TEST_F(ExporterTest, MalformedIndexIsReportedWithLine) {
  fs::create_directories(dir_);
  std::ofstream(dir_ / "index.csv") << "frame,time_s,file\n0,0,a.csv\nzero,1,b.csv\n";
  try {
    read_index(dir_ / "index.csv");
    FAIL() << "no error";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("index.csv:3:"), std::string::npos) << e.what();
  }
}

TEST(FrameFileName, IsZeroPadded) {
  EXPECT_EQ(frame_file_name(42, "vtp"), "frame_000042.vtp");
  EXPECT_EQ(frame_file_name(1234567, "csv"), "frame_1234567.csv");
}

}  // namespace
