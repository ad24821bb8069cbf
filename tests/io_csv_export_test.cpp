// CSV exporter: read back with an independent parser; every value must round-trip bit-exactly
// and rows must come in id order.
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <charconv>
#include <cstdint>
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

struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<float>> rows;
};

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream s(line);
  std::string cell;
  while (std::getline(s, cell, ',')) out.push_back(cell);
  return out;
}

Csv parse_csv(const std::string& text) {
  Csv csv;
  std::stringstream s(text);
  std::string line;
  std::getline(s, line);
  csv.header = split(line);
  while (std::getline(s, line)) {
    std::vector<float> row;
    for (const auto& cell : split(line)) {
      float f = 0;
      auto [end, ec] = std::from_chars(cell.data(), cell.data() + cell.size(), f);
      EXPECT_TRUE(ec == std::errc() || ec == std::errc::result_out_of_range) << cell;  // denormals
      EXPECT_EQ(end, cell.data() + cell.size()) << cell;
      row.push_back(f);
    }
    EXPECT_EQ(row.size(), csv.header.size()) << line;
    csv.rows.push_back(row);
  }
  return csv;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void expect_bits(float got, float want, const std::string& what) {
  EXPECT_EQ(std::bit_cast<std::uint32_t>(got), std::bit_cast<std::uint32_t>(want)) << what << ": " << got << " vs " << want;
}

class CsvExportTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(::testing::TempDir()) /
           ("rtsph_csv_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
            std::to_string(::getpid()));
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST(CsvReader, ParsesHandWrittenReference) {
  auto csv = parse_csv("x,y\n1.5,-2\n1e-45,3.4028235e+38\n");
  ASSERT_EQ(csv.header, (std::vector<std::string>{"x", "y"}));
  ASSERT_EQ(csv.rows.size(), 2u);
  expect_bits(csv.rows[0][0], 1.5f, "r0");
  expect_bits(csv.rows[0][1], -2.0f, "r0");
  expect_bits(csv.rows[1][0], std::numeric_limits<float>::denorm_min(), "r1");
  expect_bits(csv.rows[1][1], std::numeric_limits<float>::max(), "r1");
}

void check_round_trip(const fs::path& dir, int dim, std::uint32_t id_stride) {
  Fluid f(dim, 300, id_stride, 42 + dim);
  auto ex = make_exporter("csv", dir);
  ex->write_frame(0, 0.0, f.view());
  auto csv = parse_csv(slurp(dir / "frame_000000.csv"));
  const std::vector<std::string> want_header =
      dim == 2 ? std::vector<std::string>{"x", "y", "vx", "vy", "density", "pressure"}
               : std::vector<std::string>{"x", "y", "z", "vx", "vy", "vz", "density", "pressure"};
  ASSERT_EQ(csv.header, want_header);
  ASSERT_EQ(csv.rows.size(), 300u);
  auto order = f.by_id();
  for (std::size_t r = 0; r < order.size(); ++r) {
    const auto i = order[r];
    const auto& row = csv.rows[r];
    const std::string at = "row " + std::to_string(r);
    for (int k = 0; k < dim; ++k) expect_bits(row[k], f.x[k][i], at + " x");
    for (int k = 0; k < dim; ++k) expect_bits(row[dim + k], f.v[k][i], at + " v");
    expect_bits(row[2 * dim], f.rho[i], at + " density");
    expect_bits(row[2 * dim + 1], f.p[i], at + " pressure");
  }
}

TEST_F(CsvExportTest, RoundTrips2DInIdOrder) { check_round_trip(dir_, 2, 1); }
TEST_F(CsvExportTest, RoundTrips3DWithSparseIds) { check_round_trip(dir_, 3, 100'003); }

TEST_F(CsvExportTest, AttributeSelectionDropsColumns) {
  Fluid f(3, 20, 1, 7);
  auto ex = make_exporter("csv", dir_, parse_attributes("pressure,position"));
  ex->write_frame(3, 0.5, f.view());
  auto csv = parse_csv(slurp(dir_ / "frame_000003.csv"));
  ASSERT_EQ(csv.header, (std::vector<std::string>{"x", "y", "z", "pressure"}));
  auto order = f.by_id();
  for (std::size_t r = 0; r < order.size(); ++r) expect_bits(csv.rows[r][3], f.p[order[r]], "pressure");
}

TEST_F(CsvExportTest, EmptyFrameHasHeaderOnly) {
  Fluid f(2, 0, 1, 1);
  make_exporter("csv", dir_)->write_frame(0, 0.0, f.view());
  EXPECT_EQ(slurp(dir_ / "frame_000000.csv"), "x,y,vx,vy,density,pressure\n");
}

TEST_F(CsvExportTest, IndexListsEveryCompleteFrame) {
  Fluid f(2, 10, 1, 3);
  auto ex = make_exporter("csv", dir_);
  ex->write_frame(0, 0.0, f.view());
  ex->write_frame(1, 0.025, f.view());
  ex->write_frame(2, 0.05, f.view());
  EXPECT_EQ(slurp(dir_ / "index.csv"),
            "frame,time_s,file\n0,0,frame_000000.csv\n1,0.025,frame_000001.csv\n2,0.05,frame_000002.csv\n");
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir_)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"frame_000000.csv", "frame_000001.csv", "frame_000002.csv", "index.csv"}));
}

}  // namespace
