// Checkpoints: exact round trip through a fake Simulation, and a CheckpointError (never a
// crash) for every kind of damaged or mismatched file.
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "io/checkpoint.h"

namespace fs = std::filesystem;
using namespace rtsph;
using namespace rtsph::io;

namespace {

/// Just enough of a Simulation to own state fields: fluid positions/velocities/densities, a
/// clock and boundary positions, sized like a real solver's.
class FakeSim final : public Simulation {
 public:
  FakeSim(int dim, std::size_t fluid, std::size_t boundary, unsigned seed) : dim_(dim), boundary_(boundary) {
    prepare_state(fluid);
    std::mt19937 g(seed);
    for (auto* arr : {&x_, &v_, &rho_, &bx_}) {
      for (auto& f : *arr) f = std::uniform_real_distribution<float>(-5, 5)(g);
    }
    time_ = 0.25 + seed;
    bx_.resize(boundary * dim);
  }
  std::string rename_field;  // makes this solver's field list differ from a file's

  int dimension() const override { return dim_; }
  const SimSpec& spec() const override { return spec_; }
  void step() override {}
  double time() const override { return time_; }
  std::uint64_t step_count() const override { return 0; }
  SimStats stats() const override { return {}; }
  const StageTimes& stage_times() const override { return times_; }
  void reset_stage_times() override {}
  ParticleView fluid() const override {
    ParticleView v;
    v.dim = dim_;
    v.count = rho_.size();
    return v;
  }
  BoundaryView boundary() const override {
    BoundaryView b;
    b.dim = dim_;
    b.count = boundary_;
    return b;
  }
  void set_gravity(const Vec3d&) override {}
  void set_brush(const Brush&) override {}
  void move_obstacle(int, const Vec3d&) override {}
  Vec3d obstacle_center(int) const override { return {}; }
  void set_live_parameters(const SimSpec&) override {}
  void prepare_state(std::size_t n) override {
    prepared_with = n;
    x_.assign(n * dim_, 0.f);
    v_.assign(n * dim_, 0.f);
    rho_.assign(n, 0.f);
    bx_.assign(boundary_ * dim_, 0.f);
  }
  std::vector<StateField> state_fields() override {
    auto field = [](std::string name, auto& vec) {
      return StateField{std::move(name), vec.data(), vec.size() * sizeof(vec[0])};
    };
    return {field("x", x_), field("v", v_), field(rename_field.empty() ? "rho" : rename_field, rho_),
            StateField{"time", &time_, sizeof time_}, field("boundary_x", bx_)};
  }
  void state_loaded() override { ++loaded; }
  void overwrite_fluid(const float* const*, const float* const*) override {}

  bool same_state(const FakeSim& o) const {
    return x_ == o.x_ && v_ == o.v_ && rho_ == o.rho_ && bx_ == o.bx_ && time_ == o.time_;
  }
  std::size_t prepared_with = 0;
  int loaded = 0;

 private:
  int dim_;
  std::size_t boundary_;
  std::vector<float> x_, v_, rho_, bx_;
  double time_ = 0;
  SimSpec spec_;
  StageTimes times_;
};

class CheckpointTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(::testing::TempDir()) /
           ("rtsph_ckpt_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
            std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    file_ = dir_ / "state.ckpt";
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string slurp() const {
    std::ifstream in(file_, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  void overwrite(const std::string& bytes) const { std::ofstream(file_, std::ios::binary | std::ios::trunc) << bytes; }
  /// Loads into `sim` expecting a CheckpointError mentioning the file and `what`.
  void expect_error(FakeSim& sim, std::uint64_t hash, const std::string& what) const {
    try {
      read_checkpoint(file_, sim, hash);
      ADD_FAILURE() << "no error, expected " << what;
    } catch (const CheckpointError& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find(file_.string()), std::string::npos) << msg;
      EXPECT_NE(msg.find(what), std::string::npos) << msg;
      EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    }
  }
  fs::path dir_, file_;
  static constexpr std::uint64_t kHash = 0x1234'5678'9abc'def0ULL;
};

TEST(HashBytes, MatchesFnv1a64ReferenceValues) {
  EXPECT_EQ(hash_bytes(""), 0xcbf29ce484222325ULL);
  EXPECT_EQ(hash_bytes("a"), 0xaf63dc4c8601ec8cULL);
  EXPECT_EQ(hash_bytes("foobar"), 0x85944171f73967e8ULL);
}

TEST_F(CheckpointTest, RoundTripRestoresEveryField) {
  FakeSim a(3, 100, 40, 1), b(3, 7, 40, 2);
  write_checkpoint(file_, a, kHash);
  read_checkpoint(file_, b, kHash);
  EXPECT_EQ(b.prepared_with, 100u);
  EXPECT_EQ(b.loaded, 1);
  EXPECT_TRUE(b.same_state(a));
}

TEST_F(CheckpointTest, LayoutStartsWithTheDocumentedHeader) {
  FakeSim a(2, 10, 4, 1);
  write_checkpoint(file_, a, kHash);
  const auto f = slurp();
  ASSERT_GE(f.size(), 44u);
  EXPECT_EQ(f.substr(0, 8), std::string("RTSPHCK\0", 8));
  std::uint32_t version, dim, fields;
  std::uint64_t fluid, boundary, hash;
  std::memcpy(&version, f.data() + 8, 4);
  std::memcpy(&dim, f.data() + 12, 4);
  std::memcpy(&fluid, f.data() + 16, 8);
  std::memcpy(&boundary, f.data() + 24, 8);
  std::memcpy(&hash, f.data() + 32, 8);
  std::memcpy(&fields, f.data() + 40, 4);
  EXPECT_EQ(version, kCheckpointVersion);
  EXPECT_EQ(dim, 2u);
  EXPECT_EQ(fluid, 10u);
  EXPECT_EQ(boundary, 4u);
  EXPECT_EQ(hash, kHash);
  EXPECT_EQ(fields, 5u);
  std::uint64_t checksum;
  std::memcpy(&checksum, f.data() + f.size() - 8, 8);
  EXPECT_EQ(checksum, hash_bytes(std::string_view(f).substr(0, f.size() - 8)));
}

TEST_F(CheckpointTest, EveryTruncationIsReported) {
  FakeSim a(2, 5, 3, 1);
  write_checkpoint(file_, a, kHash);
  const auto full = slurp();
  for (std::size_t len = 0; len < full.size(); ++len) {
    overwrite(full.substr(0, len));
    FakeSim b(2, 1, 3, 2);
    expect_error(b, kHash, "truncated");
    EXPECT_EQ(b.loaded, 0);
  }
}

TEST_F(CheckpointTest, EveryFlippedByteIsReported) {
  FakeSim a(2, 5, 3, 1);
  write_checkpoint(file_, a, kHash);
  const auto full = slurp();
  for (std::size_t i = 0; i < full.size(); ++i) {
    auto bad = full;
    bad[i] = static_cast<char>(bad[i] ^ 0x10);
    overwrite(bad);
    FakeSim b(2, 1, 3, 2);
    EXPECT_THROW(read_checkpoint(file_, b, kHash), CheckpointError) << "byte " << i;
    EXPECT_EQ(b.loaded, 0);
  }
  // A flip inside field data can only be caught by the checksum.
  auto bad = full;
  bad[full.size() - 20] ^= 1;
  overwrite(bad);
  FakeSim b(2, 1, 3, 2);
  expect_error(b, kHash, "checksum mismatch");
}

TEST_F(CheckpointTest, WrongMagic) {
  overwrite(std::string("NOTACKPT") + std::string(100, '\0'));
  FakeSim b(3, 1, 3, 2);
  expect_error(b, kHash, "bad magic");
}

TEST_F(CheckpointTest, UnsupportedVersion) {
  FakeSim a(3, 5, 3, 1);
  write_checkpoint(file_, a, kHash);
  auto f = slurp();
  f[8] = 9;
  overwrite(f);
  expect_error(a, kHash, "unsupported version 9");
}

TEST_F(CheckpointTest, SceneHashMismatchLeavesTheSimulationUntouched) {
  FakeSim a(3, 5, 3, 1), b(3, 8, 3, 2);
  write_checkpoint(file_, a, kHash);
  b.prepared_with = 0;
  expect_error(b, kHash + 1, "scene hash mismatch");
  EXPECT_EQ(b.prepared_with, 0u);
}

TEST_F(CheckpointTest, DimensionMismatch) {
  FakeSim a(2, 5, 3, 1), b(3, 5, 3, 2);
  write_checkpoint(file_, a, kHash);
  expect_error(b, kHash, "dimension mismatch");
}

TEST_F(CheckpointTest, BoundaryCountMismatch) {
  FakeSim a(3, 5, 3, 1), b(3, 5, 4, 2);
  write_checkpoint(file_, a, kHash);
  expect_error(b, kHash, "boundary count mismatch");
}

TEST_F(CheckpointTest, FieldNameMismatch) {
  FakeSim a(3, 5, 3, 1), b(3, 5, 3, 2);
  write_checkpoint(file_, a, kHash);
  b.rename_field = "density";
  expect_error(b, kHash, "field 2 is 'rho' of 20 bytes, the solver expects 'density' of 20 bytes");
  EXPECT_EQ(b.loaded, 0);
}

TEST_F(CheckpointTest, MissingFileAndGarbage) {
  FakeSim b(3, 5, 3, 2);
  expect_error(b, kHash, "cannot open");
  std::mt19937 g(3);
  for (int trial = 0; trial < 200; ++trial) {
    std::string junk(g() % 300, '\0');
    for (auto& c : junk) c = static_cast<char>(g());
    if (trial % 2) junk.replace(0, std::min<std::size_t>(8, junk.size()), std::string("RTSPHCK\0\1\0\0\0", 12), 0, 8);
    overwrite(junk);
    EXPECT_THROW(read_checkpoint(file_, b, kHash), CheckpointError);
  }
}

TEST_F(CheckpointTest, WriteIntoMissingDirectoryThrowsIoError) {
  FakeSim a(3, 5, 3, 1);
  EXPECT_THROW(write_checkpoint(dir_ / "nope" / "x.ckpt", a, kHash), IoError);
}

}  // namespace
