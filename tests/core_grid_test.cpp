// Uniform-grid neighbour search (src/core/grid.h) and the 8-lane candidate loop
// (src/core/pair_loop.h) against brute force. The property under test: after build() and
// reordering by order(), the candidates of for_each_range filtered by r² < support² are EXACTLY
// the brute-force O(N²) neighbour set of every particle (support = cell size), for random sets
// and the edge cases (empty, single particle, one cell, cell borders and ±ulp around them,
// dense clusters, points outside the box, NaN), 2D and 3D, with 1 and 2 threads.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "core/aligned_array.h"
#include "core/grid.h"
#include "core/neighbour_list.h"
#include "core/pair_loop.h"
#include "core/parallel.h"
#include "core/simd.h"

namespace rtsph {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

template <int D>
using Points = std::vector<std::array<float, D>>;

// One definition of the pair distance used by both the grid side and the brute-force side, kept
// out of line so the compiler cannot contract (FMA) it differently in the two loops.
template <int D>
__attribute__((noinline)) float dist2(const float* const xs[D], std::size_t i, std::size_t j) {
  float r2 = 0;
  for (int a = 0; a < D; ++a) {
    const float d = xs[a][i] - xs[a][j];
    r2 += d * d;
  }
  return r2;
}

/// Failures recorded so far in the running test, so a helper can stop after its own fatal
/// failure without being silenced by an earlier, unrelated one.
int failures() {
  return ::testing::UnitTest::GetInstance()->current_test_info()->result()->total_part_count();
}

template <int D>
struct Built {
  UniformGrid<D> grid;
  AlignedArray<float> sorted[D];  // positions reordered by order(), padded for 8-wide loads
  const float* ptr[D];
};

template <int D, class P>
void build(Built<D>& b, const P& pts, const Vec<D>& lo, const Vec<D>& hi, float cell,
           int threads) {
  const std::size_t n = pts.size();
  std::vector<float> in[D];
  const float* inp[D];
  for (int a = 0; a < D; ++a) {
    in[a].resize(n);
    for (std::size_t i = 0; i < n; ++i) in[a][i] = pts[i][a];
    inp[a] = in[a].data();
  }
  b.grid.configure(lo, hi, cell);
  b.grid.build(inp, n, ThreadPool(threads));
  for (int a = 0; a < D; ++a) {
    b.sorted[a].resize(n);
    for (std::size_t i = 0; i < n; ++i) b.sorted[a][i] = in[a][b.grid.order()[i]];
    b.ptr[a] = b.sorted[a].data();
  }
}

/// Structural invariants of a built grid.
template <int D, class P>
void check_structure(const Built<D>& b, const P& pts, const std::string& what) {
  const auto& g = b.grid;
  const std::size_t n = pts.size();
  ASSERT_EQ(g.particle_count(), n) << what;
  // order() is a permutation of [0, n).
  std::vector<char> seen(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const uint32_t o = g.order()[i];
    ASSERT_LT(o, n) << what << ": order()[" << i << "] out of range";
    ASSERT_FALSE(seen[o]) << what << ": order() repeats " << o;
    seen[o] = 1;
  }
  // cell_start is monotone from 0 to n.
  const uint32_t* s = g.cell_start();
  ASSERT_EQ(s[0], 0u) << what;
  for (std::size_t c = 0; c < g.cell_count(); ++c) ASSERT_LE(s[c], s[c + 1]) << what << " cell " << c;
  ASSERT_EQ(s[g.cell_count()], n) << what << ": cell_start[last] != n";
  // sorted_cells agrees with cell_of, with cell_start, and the sort is stable.
  for (std::size_t i = 0; i < n; ++i) {
    const uint32_t key = g.sorted_cells()[i];
    Vec<D> p;
    for (int a = 0; a < D; ++a) p[a] = pts[g.order()[i]][a];
    ASSERT_EQ(key, g.cell_of(p)) << what << " sorted " << i;
    ASSERT_LT(key, g.cell_count()) << what;
    ASSERT_GE(i, s[key]) << what;
    ASSERT_LT(i, s[key + 1]) << what;
    // Never a padding cell: every key has interior coordinates 1..dims-2.
    uint32_t k = key;
    for (int a = 0; a < D; ++a) {
      const int c = int(k % uint32_t(g.dim(a)));
      k /= uint32_t(g.dim(a));
      ASSERT_GE(c, 1) << what << " axis " << a;
      ASSERT_LE(c, g.dim(a) - 2) << what << " axis " << a;
    }
    if (i > 0) {
      ASSERT_LE(g.sorted_cells()[i - 1], key) << what << ": keys not sorted at " << i;
      if (g.sorted_cells()[i - 1] == key) {
        ASSERT_LT(g.order()[i - 1], g.order()[i]) << what << ": sort not stable at " << i;
      }
    }
  }
}

/// Grid neighbours == brute force for every particle. Uses stamps instead of stored sets so
/// dense clusters (10^8 pairs) need O(N) memory.
template <int D>
void check_neighbours(const Built<D>& b, std::size_t n, float cell, const std::string& what) {
  const int failures_before = failures();
  const float support2 = cell * cell;
  std::vector<uint32_t> brute_stamp(n, UINT32_MAX), grid_stamp(n, UINT32_MAX);
  std::size_t total = 0, missed = 0, missing_particles = 0;
  std::string first_miss;
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t nb = 0;
    for (std::size_t j = 0; j < n; ++j)
      if (dist2<D>(b.ptr, i, j) < support2) { brute_stamp[j] = uint32_t(i); ++nb; }
    std::size_t found = 0;
    b.grid.for_each_range(b.grid.sorted_cells()[i], [&](uint32_t begin, uint32_t end) {
      ASSERT_LE(begin, end) << what;
      ASSERT_LE(end, n) << what;
      for (uint32_t j = begin; j < end; ++j) {
        if (!(dist2<D>(b.ptr, i, j) < support2)) continue;
        ASSERT_NE(grid_stamp[j], uint32_t(i)) << what << ": candidate " << j << " visited twice";
        grid_stamp[j] = uint32_t(i);
        ASSERT_EQ(brute_stamp[j], uint32_t(i))
            << what << ": grid reports a non-neighbour " << j << " of " << i;
        ++found;
      }
    });
    if (failures() != failures_before) return;
    total += nb;
    if (found == nb) continue;
    missed += nb - found;
    ++missing_particles;
    if (!first_miss.empty()) continue;
    // Describe the first missed pair.
    for (std::size_t j = 0; j < n && first_miss.empty(); ++j) {
      if (brute_stamp[j] != uint32_t(i) || grid_stamp[j] == uint32_t(i)) continue;
      Vec<D> vi, vj;
      std::string pi, pj;
      for (int a = 0; a < D; ++a) {
        vi[a] = b.ptr[a][i];
        vj[a] = b.ptr[a][j];
        pi += std::to_string(vi[a]) + " ";
        pj += std::to_string(vj[a]) + " ";
      }
      char buf[256];
      std::snprintf(buf, sizeof buf, " r2=%.9g < support2=%.9g, cells %u vs %u", dist2<D>(b.ptr, i, j),
                    support2, b.grid.cell_of(vi), b.grid.cell_of(vj));
      // Diagnose the known failure mode: the cell index f = (p - origin) * (1/cell) rounds, so
      // two particles closer than one cell can get indices two apart on one axis and fall
      // outside each other's 3^D stencil.
      std::string why;
      const Real inv = Real(1) / b.grid.cell_size();
      for (int a = 0; a < D; ++a) {
        const Real fi = (vi[a] - b.grid.origin()[a]) * inv, fj = (vj[a] - b.grid.origin()[a]) * inv;
        if (std::abs(int(fi) - int(fj)) >= 2) {
          char w[200];
          std::snprintf(w, sizeof w, " axis %d: f=(p-origin)*inv_cell = %.9g vs %.9g -> cells %d, %d",
                        a, double(fi), double(fj), int(fi), int(fj));
          why += w;
        }
      }
      if (!why.empty())
        why = " | BUG src/core/grid.cpp:32-34 (UniformGrid::cell_of): rounding of the cell index "
              "puts particles closer than one cell two cells apart, so for_each_range never "
              "visits the pair;" + why;
      first_miss = "first: j=" + std::to_string(j) + " (" + pj + ") of i=" + std::to_string(i) +
                   " (" + pi + ")" + buf + why;
    }
  }
  EXPECT_EQ(missed, 0u) << what << ": grid MISSES " << missed << " of " << total
                        << " neighbour pairs (" << missing_particles << " particles affected); "
                        << first_miss;
  ::testing::Test::RecordProperty(what + "_pairs", std::to_string(total));
}

/// Full check: structure and neighbour sets with 1 thread, and bitwise-equal build with 2.
template <int D>
void check_all(const Points<D>& pts, const Vec<D>& lo, const Vec<D>& hi, float cell,
               const std::string& what) {
  SCOPED_TRACE(what);
  Built<D> one, two;
  build(one, pts, lo, hi, cell, 1);
  build(two, pts, lo, hi, cell, 2);
  const std::size_t n = pts.size();
  const int failures_before = failures();
  check_structure(one, pts, what);
  if (failures() != failures_before) return;
  ASSERT_EQ(one.grid.cell_count(), two.grid.cell_count());
  for (std::size_t i = 0; i < n; ++i) {
    ASSERT_EQ(one.grid.order()[i], two.grid.order()[i]) << what << ": 1 vs 2 threads, order " << i;
    ASSERT_EQ(one.grid.sorted_cells()[i], two.grid.sorted_cells()[i]) << what << ": 1 vs 2 threads";
  }
  for (std::size_t c = 0; c <= one.grid.cell_count(); ++c)
    ASSERT_EQ(one.grid.cell_start()[c], two.grid.cell_start()[c]) << what << ": 1 vs 2 threads";
  check_neighbours(one, n, cell, what);
}

template <int D>
Vec<D> vec(float v) { return Vec<D>::splat(v); }

template <int D>
Points<D> uniform(std::size_t n, float lo, float hi, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(lo, hi);
  Points<D> p(n);
  for (auto& q : p)
    for (int a = 0; a < D; ++a) q[a] = u(rng);
  return p;
}

template <class T>
class GridTest : public ::testing::Test {};
template <int D_>
struct Dim { static constexpr int D = D_; };
using Dims = ::testing::Types<Dim<2>, Dim<3>>;
TYPED_TEST_SUITE(GridTest, Dims);

TYPED_TEST(GridTest, UniformRandomMatchesBruteForce) {
  constexpr int D = TypeParam::D;
  const std::size_t n = D == 2 ? 3000 : 4000;
  check_all<D>(uniform<D>(n, -0.3f, 0.7f, 1), vec<D>(-0.3f), vec<D>(0.7f), 0.1f, "uniform cell 0.1");
  check_all<D>(uniform<D>(n, 0.0f, 1.0f, 2), vec<D>(0.0f), vec<D>(1.0f), 0.0625f, "uniform cell 1/16");
  // A cell size that does not divide the box, and an anisotropic box.
  Vec<D> hi = vec<D>(0.5f);
  hi[0] = 1.3f;
  auto p = uniform<D>(n, 0.0f, 0.5f, 3);
  for (auto& q : p) q[0] *= 2.6f;
  check_all<D>(p, vec<D>(0.0f), hi, 0.07f, "anisotropic cell 0.07");
}

TYPED_TEST(GridTest, EmptyAndSingle) {
  constexpr int D = TypeParam::D;
  check_all<D>(Points<D>{}, vec<D>(0.0f), vec<D>(1.0f), 0.1f, "empty");
  check_all<D>(Points<D>(1), vec<D>(0.0f), vec<D>(1.0f), 0.1f, "single at lo");
  Points<D> one(1);
  for (int a = 0; a < D; ++a) one[0][a] = 0.55f;
  check_all<D>(one, vec<D>(0.0f), vec<D>(1.0f), 0.1f, "single inside");
  // A degenerate box (hi == lo) still yields a working one-cell grid.
  check_all<D>(uniform<D>(20, 0.0f, 0.05f, 4), vec<D>(0.0f), vec<D>(0.0f), 0.1f, "zero-size box");
}

TYPED_TEST(GridTest, AllInOneCell) {
  constexpr int D = TypeParam::D;
  // Cell [0.3, 0.4)^D: n not a multiple of 8.
  check_all<D>(uniform<D>(61, 0.301f, 0.399f, 5), vec<D>(0.0f), vec<D>(1.0f), 0.1f, "one cell");
  // Every particle at the same point.
  Points<D> same(37);
  for (auto& q : same)
    for (int a = 0; a < D; ++a) q[a] = 0.25f;
  check_all<D>(same, vec<D>(0.0f), vec<D>(1.0f), 0.1f, "coincident");
}

TYPED_TEST(GridTest, ParticlesOnCellBorders) {
  constexpr int D = TypeParam::D;
  // Lattice points k·cell for every k from lo to hi inclusive, so neighbours sit exactly one cell
  // apart (r² == support² up to float rounding) and the domain bounds themselves are occupied.
  for (const float cell : {0.25f, 0.1f, 0.07f}) {
    for (const float lo : {0.0f, -0.35f}) {
      const int k = D == 2 ? 14 : 8;
      const float hi = lo + float(k) * cell;
      Points<D> p;
      std::array<float, D> q{};
      int idx[D] = {};
      while (true) {
        for (int a = 0; a < D; ++a) q[a] = lo + float(idx[a]) * cell;
        if (D > 1) q[D - 1] = float(double(lo) + double(idx[D - 1]) * double(cell));  // other rounding
        p.push_back(q);
        int a = 0;
        while (a < D && ++idx[a] > k) idx[a++] = 0;
        if (a == D) break;
      }
      check_all<D>(p, vec<D>(lo), vec<D>(hi), cell,
                   "lattice cell " + std::to_string(cell) + " lo " + std::to_string(lo));
    }
  }
}

// KNOWN BUG (fails until fixed in src/core/grid.cpp): cell_of computes the index as
// int((p - origin) * inv_cell) in float, so e.g. x = 0.5 and x = 0.6 with cell 0.1, lo -0.2 get
// f = 7.9999995 and 9.0 -> cells 7 and 9 although their float r² = 0.00999999885 < 0.01; the pair
// is never visited. Same for the 2D lattice with cell 0.07 in ParticlesOnCellBorders.
TYPED_TEST(GridTest, ParticlesWithinUlpsOfCellBorders) {
  constexpr int D = TypeParam::D;
  // Border coordinates nudged by -2..+2 ulps: pairs at distance one cell minus a few ulps must
  // still be found even when rounding in the cell index moves a particle across a border.
  std::mt19937 rng(6);
  for (const float cell : {0.1f, 0.07f, 0.3f}) {
    const float lo = -0.2f;
    const int k = D == 2 ? 10 : 6;
    const float hi = lo + float(k) * cell;
    Points<D> p;
    std::uniform_int_distribution<int> ki(0, k), ulp(-2, 2);
    for (int t = 0; t < (D == 2 ? 3000 : 4000); ++t) {
      std::array<float, D> q;
      for (int a = 0; a < D; ++a) {
        float v = lo + float(ki(rng)) * cell;
        const int u = ulp(rng);
        for (int s = 0; s < std::abs(u); ++s) v = std::nextafter(v, u > 0 ? kInf : -kInf);
        q[a] = v;
      }
      p.push_back(q);
    }
    check_all<D>(p, vec<D>(lo), vec<D>(hi), cell, "ulp-nudged borders cell " + std::to_string(cell));
  }
}

TYPED_TEST(GridTest, DenseClusterOf10000InOneCell) {
  constexpr int D = TypeParam::D;
  check_all<D>(uniform<D>(10000, 0.5001f, 0.5999f, 7), vec<D>(0.0f), vec<D>(1.0f), 0.1f,
               "dense cluster");
}

TYPED_TEST(GridTest, ParticlesOutsideTheBoxAreClamped) {
  constexpr int D = TypeParam::D;
  // Half inside [0,1]^D, half in [-0.5, 1.5]^D, plus far-away and infinite coordinates.
  auto p = uniform<D>(1500, 0.0f, 1.0f, 8);
  auto out = uniform<D>(1500, -0.5f, 1.5f, 9);
  p.insert(p.end(), out.begin(), out.end());
  for (float far : {1e6f, -1e6f, 1e30f, -1e30f, kInf, -kInf, 1.05f, -0.05f}) {
    std::array<float, D> q;
    for (int a = 0; a < D; ++a) q[a] = 0.5f;
    q[0] = far;
    p.push_back(q);
    p.push_back(q);  // a coincident twin far outside must still be found
    for (int a = 0; a < D; ++a) q[a] = far;
    p.push_back(q);
  }
  check_all<D>(p, vec<D>(0.0f), vec<D>(1.0f), 0.1f, "outside box");
}

TYPED_TEST(GridTest, NaNCoordinatesDoNotCrash) {
  constexpr int D = TypeParam::D;
  auto p = uniform<D>(500, 0.0f, 1.0f, 10);
  for (int t = 0; t < 40; ++t) {
    auto& q = p[std::size_t(t) * 11];
    q[t % D] = kNaN;
    if (t % 3 == 0)
      for (int a = 0; a < D; ++a) q[a] = kNaN;
  }
  // NaN pairs have r² = NaN, never < support², so brute force gives them no neighbours at all;
  // the grid must agree and the others must be unaffected.
  check_all<D>(p, vec<D>(0.0f), vec<D>(1.0f), 0.1f, "NaN");
  Points<D> all_nan(9);
  for (auto& q : all_nan)
    for (int a = 0; a < D; ++a) q[a] = kNaN;
  check_all<D>(all_nan, vec<D>(0.0f), vec<D>(1.0f), 0.1f, "all NaN");
}

TYPED_TEST(GridTest, StableCountingSortWithManyEqualKeys) {
  constexpr int D = TypeParam::D;
  // Few cells, many particles per cell, interleaved input: stability is visible.
  Points<D> p;
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> c(0, 2);
  std::uniform_real_distribution<float> f(0.01f, 0.99f);
  for (int i = 0; i < 3000; ++i) {
    std::array<float, D> q;
    for (int a = 0; a < D; ++a) q[a] = (float(c(rng)) + f(rng)) * 0.25f;
    p.push_back(q);
  }
  check_all<D>(p, vec<D>(0.0f), vec<D>(0.75f), 0.25f, "stable");
}

TYPED_TEST(GridTest, RebuildAfterReconfigure) {
  constexpr int D = TypeParam::D;
  Built<D> b;
  auto big = uniform<D>(3000, 0.0f, 2.0f, 12);
  build(b, big, vec<D>(0.0f), vec<D>(2.0f), 0.1f, 2);
  check_structure(b, big, "big");
  auto small = uniform<D>(800, 0.0f, 0.5f, 13);
  build(b, small, vec<D>(0.0f), vec<D>(0.5f), 0.125f, 2);
  check_structure(b, small, "small after big");
  check_neighbours(b, small.size(), 0.125f, "small after big");
}

// ---- for_each_candidate_batch -------------------------------------------------------------

/// The mask of every batch selects exactly the in-range, in-support lanes; offsets and r² are
/// those of the selected candidates; and the union over batches is the brute-force neighbour set.
template <int D>
void check_batches(const Built<D>& b, std::size_t n, float cell, const std::string& what,
                   std::size_t* boundary_ties = nullptr) {
  using simd::f8;
  using simd::i8;
  const float support2 = cell * cell;
  std::vector<uint32_t> stamp(n, UINT32_MAX);
  for (std::size_t i = 0; i < n; ++i) {
    float xi[D];
    for (int a = 0; a < D; ++a) xi[a] = b.ptr[a][i];
    const uint32_t cell_i = b.grid.sorted_cells()[i];
    std::vector<std::pair<uint32_t, uint32_t>> ranges;
    b.grid.for_each_range(cell_i, [&](uint32_t s, uint32_t e) { ranges.emplace_back(s, e); });
    std::size_t selected = 0, batches = 0;
    for_each_candidate_batch<D, false>(b.grid, cell_i, b.ptr, xi, support2,
                                [&](uint32_t j, const f8* d, f8 r2, i8 m) {
      ++batches;
      uint32_t end = 0;
      for (auto [s, e] : ranges)
        if (s <= j && j < e) end = e;
      ASSERT_NE(end, 0u) << what << ": batch start " << j << " is in no range of cell " << cell_i;
      for (int l = 0; l < simd::kWidth; ++l) {
        const uint32_t idx = j + uint32_t(l);
        const bool in_range = idx < end;
        const bool expect = in_range && r2[l] < support2;
        ASSERT_EQ(m[l] != 0, expect) << what << ": lane " << l << " of batch " << j << " (end " << end
                                     << ", r2 " << r2[l] << ") for particle " << i;
        if (m[l]) {
          ASSERT_EQ(m[l], -1) << what << ": mask lanes are all-ones";
        }
        if (!in_range) continue;
        float r2s = 0;
        for (int a = 0; a < D; ++a) {
          const float expect_d = xi[a] - b.ptr[a][idx];
          ASSERT_TRUE(d[a][l] == expect_d || (std::isnan(d[a][l]) && std::isnan(expect_d)))
              << what << ": offset lane " << l << ": " << d[a][l] << " vs " << expect_d;
          r2s += d[a][l] * d[a][l];
        }
        // r² may be FMA-contracted in the vector loop: equal to a few ulps.
        if (std::isnan(r2s)) {
          ASSERT_TRUE(std::isnan(r2[l])) << what << ": NaN candidate lost its NaN";
        } else {
          ASSERT_NEAR(r2[l], r2s, 4e-7f * r2s + 1e-30f) << what;
        }
        if (m[l]) {
          ASSERT_NE(stamp[idx], uint32_t(i)) << what << ": candidate selected twice";
          stamp[idx] = uint32_t(i);
          ++selected;
        }
      }
    });
    if (::testing::Test::HasFatalFailure()) return;  // no earlier failures in these tests
    // Against brute force. A pair whose r² lies within a few ulps of support² may be classified
    // either way depending on FMA contraction; count those and accept either answer.
    std::size_t nb = 0;
    for (std::size_t j = 0; j < n; ++j) {
      const float r2 = dist2<D>(b.ptr, i, j);
      const bool tie = std::abs(r2 - support2) <= 4e-7f * support2;
      if (tie) {
        if (boundary_ties) ++*boundary_ties;
        if (stamp[j] == uint32_t(i)) ++nb;
        continue;
      }
      if (r2 < support2) {
        ++nb;
        ASSERT_EQ(stamp[j], uint32_t(i)) << what << ": batch loop misses neighbour " << j << " of " << i;
      } else {
        ASSERT_NE(stamp[j], uint32_t(i)) << what << ": batch loop selects non-neighbour " << j;
      }
    }
    ASSERT_EQ(selected, nb) << what << " particle " << i;
  }
}

template <int D, class P>
void check_batches_for(const P& pts, const Vec<D>& lo, const Vec<D>& hi, float cell,
                       const std::string& what) {
  Built<D> b;
  build(b, pts, lo, hi, cell, 2);
  std::size_t ties = 0;
  check_batches(b, pts.size(), cell, what, &ties);
  if (what != "exact lattice") {
    EXPECT_LE(ties, pts.size() / 100 + 2) << what << ": implausibly many boundary ties";
  } else {
    EXPECT_GT(ties, pts.size()) << what << ": the lattice should have pairs at exactly one cell";
  }
}

TYPED_TEST(GridTest, CandidateBatchMatchesBruteForce) {
  constexpr int D = TypeParam::D;
  check_batches_for<D>(uniform<D>(D == 2 ? 3000 : 4000, -0.3f, 0.7f, 21), vec<D>(-0.3f),
                       vec<D>(0.7f), 0.1f, "uniform");
  check_batches_for<D>(uniform<D>(2000, 0.5001f, 0.5999f, 22), vec<D>(0.0f), vec<D>(1.0f), 0.1f,
                       "cluster");
  auto p = uniform<D>(1000, 0.0f, 1.0f, 23);
  auto out = uniform<D>(500, -0.5f, 1.5f, 24);
  p.insert(p.end(), out.begin(), out.end());
  p[3][0] = kNaN;
  check_batches_for<D>(p, vec<D>(0.0f), vec<D>(1.0f), 0.1f, "outside + NaN");
  // Exact lattice with a representable cell: many pairs at r² == support² exactly, which the
  // strict r² < support² mask must leave out.
  Points<D> lat;
  {
    const int k = D == 2 ? 12 : 6;
    int idx[D] = {};
    while (true) {
      std::array<float, D> q;
      for (int a = 0; a < D; ++a) q[a] = float(idx[a]) * 0.25f;
      lat.push_back(q);
      int a = 0;
      while (a < D && ++idx[a] > k) idx[a++] = 0;
      if (a == D) break;
    }
  }
  check_batches_for<D>(lat, vec<D>(0.0f), vec<D>(float(D == 2 ? 3.0 : 1.5)), 0.25f, "exact lattice");
  check_batches_for<D>(Points<D>{}, vec<D>(0.0f), vec<D>(1.0f), 0.1f, "empty");
  check_batches_for<D>(Points<D>(1), vec<D>(0.0f), vec<D>(1.0f), 0.1f, "single");
}

// Lanes past a range end read the array's padding. Fill that padding with positions right on
// top of the particles: only the in_range part of the mask keeps them out.
TYPED_TEST(GridTest, CandidateBatchMasksLanesPastRangeEnd) {
  constexpr int D = TypeParam::D;
  for (std::size_t n : {1u, 5u, 7u, 8u, 9u, 13u}) {
    Points<D> p(n);
    for (std::size_t i = 0; i < n; ++i)
      for (int a = 0; a < D; ++a) p[i][a] = 0.35f + 0.001f * float(i);
    Built<D> b;
    build(b, p, vec<D>(0.0f), vec<D>(1.0f), 0.1f, 1);
    for (int a = 0; a < D; ++a)
      for (std::size_t k = n; k < n + simd::kWidth; ++k) b.sorted[a][k] = 0.35f;  // into the pad
    check_batches(b, n, 0.1f, "pad n=" + std::to_string(n));
    if (::testing::Test::HasFatalFailure()) return;  // no earlier failures in these tests
  }
}

// NeighbourList (core/neighbour_list.h): each particle's list is exactly its brute-force
// neighbour set (itself included), the lists lie back to back from slot 0, each starting at a
// multiple of 8 and padded with i, and the whole layout is the same for 1 and 2 threads. A
// dense cluster has more neighbours than the first guess of the stride, so the walk repeats.
template <int D>
void check_list(const Points<D>& pts, float cell, const std::string& what) {
  Built<D> b;
  build<D>(b, pts, vec<D>(0.0f), vec<D>(1.0f), cell, 1);
  const std::size_t n = pts.size();
  NeighbourList<D> one, two;
  one.build(b.grid, b.ptr, n, cell * cell, ThreadPool(1));
  two.build(b.grid, b.ptr, n, cell * cell, ThreadPool(2));
  ASSERT_TRUE(one.valid()) << what;
  std::size_t slot = 0;
  for (std::size_t i = 0; i < n; ++i) {
    ASSERT_EQ(one.first_slot(i), slot) << what << " particle " << i;
    ASSERT_EQ(slot % 8, 0u) << what;
    std::vector<uint32_t> want;
    for (std::size_t j = 0; j < n; ++j)
      if (dist2<D>(b.ptr, i, j) < cell * cell) want.push_back(uint32_t(j));
    const uint32_t c = one.count(i);
    std::vector<uint32_t> got(one.begin(i), one.begin(i) + c);
    std::sort(got.begin(), got.end());
    ASSERT_EQ(got, want) << what << " particle " << i;
    const uint32_t padded = (c + 7u) & ~7u;
    for (uint32_t s = c; s < padded; ++s) ASSERT_EQ(one.begin(i)[s], uint32_t(i)) << what;
    ASSERT_EQ(two.first_slot(i), slot) << what;
    ASSERT_EQ(two.count(i), c) << what;
    for (uint32_t s = 0; s < padded; ++s) ASSERT_EQ(two.begin(i)[s], one.begin(i)[s]) << what;
    slot += padded;
  }
  EXPECT_EQ(one.slots(), slot) << what;
  EXPECT_EQ(two.slots(), slot) << what;
}

TYPED_TEST(GridTest, NeighbourListsArePackedAndMatchBruteForce) {
  constexpr int D = TypeParam::D;
  check_list<D>(uniform<D>(D == 2 ? 3000 : 4000, 0.0f, 1.0f, 31), 0.06f, "uniform");
  // ~600 particles within one support radius: past the first stride (24 in 2D, 64 in 3D).
  auto p = uniform<D>(600, 0.5f, 0.52f, 32);
  auto q = uniform<D>(400, 0.0f, 1.0f, 33);
  p.insert(p.end(), q.begin(), q.end());
  check_list<D>(p, 0.05f, "cluster");
  check_list<D>(Points<D>{}, 0.05f, "empty");
}

}  // namespace
}  // namespace rtsph
