// The 8-lane candidate loop (src/core/pair_loop.h) and the packed neighbour lists
// (src/core/neighbour_list.h) against brute force, over grids built as core_grid_test.cpp builds
// them (grid_test_util.h).
#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <vector>

#include "grid_test_util.h"

namespace rtsph::grid_test {
namespace {

TYPED_TEST_SUITE(GridTest, Dims);

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

// The packed list walk (positions read as records: 8-byte (x, y) in 2D, 16-byte (x, y, z, ·) in
// 3D) hands fn the same lanes, offsets, r² and mask as the gathered walk, bit for bit: the
// solvers switch between them (FluidWorld::pack_positions) and promise the same results.
TYPED_TEST(GridTest, PackedListWalkMatchesTheGatheredWalk) {
  constexpr int D = TypeParam::D;
  using simd::f8;
  using simd::i8;
  const float cell = D == 2 ? 0.06f : 0.12f;  // about 30 neighbours each
  const auto pts = uniform<D>(D == 2 ? 3000 : 4000, 0.0f, 1.0f, 34);
  Built<D> b;
  build<D>(b, pts, vec<D>(0.0f), vec<D>(1.0f), cell, 1);
  const std::size_t n = pts.size();
  NeighbourList<D> list;
  list.build(b.grid, b.ptr, n, cell * cell, ThreadPool(1));
  constexpr std::size_t stride = D == 3 ? 4 : 2;
  AlignedArray<float> rec;
  rec.resize(stride * n);
  for (std::size_t i = 0; i < n; ++i)
    for (int a = 0; a < D; ++a) rec[stride * i + a] = b.ptr[a][i];
  std::size_t batches = 0, lanes = 0;
  for (std::size_t i = 0; i < n; ++i) {
    float xi[D];
    for (int a = 0; a < D; ++a) xi[a] = b.ptr[a][i];
    std::vector<std::array<f8, D + 1>> gathered;
    std::vector<i8> gathered_j, gathered_m;
    for_each_listed_batch<D>(list, i, b.ptr, xi, cell * cell, [&](i8 j, const f8* d, f8 r2, i8 m) {
      std::array<f8, D + 1> v;
      for (int a = 0; a < D; ++a) v[a] = d[a];
      v[D] = r2;
      gathered.push_back(v);
      gathered_j.push_back(j);
      gathered_m.push_back(m);
    });
    std::size_t k = 0;
    for_each_listed_batch_packed<D>(list, i, rec.data(), xi, cell * cell, [&](i8 j, const f8* d, f8 r2, i8 m) {
      ASSERT_LT(k, gathered.size()) << "particle " << i;
      for (int l = 0; l < simd::kWidth; ++l) {
        ASSERT_EQ(j[l], gathered_j[k][l]) << "particle " << i << " batch " << k << " lane " << l;
        ASSERT_EQ(m[l], gathered_m[k][l]) << "particle " << i << " batch " << k << " lane " << l;
        if (!m[l]) continue;
        ++lanes;
        for (int a = 0; a < D; ++a)
          ASSERT_EQ(std::bit_cast<uint32_t>(d[a][l]), std::bit_cast<uint32_t>(gathered[k][a][l]))
              << "particle " << i << " axis " << a;
        ASSERT_EQ(std::bit_cast<uint32_t>(r2[l]), std::bit_cast<uint32_t>(gathered[k][D][l])) << "particle " << i;
      }
      ++k;
    });
    ASSERT_EQ(k, gathered.size()) << "particle " << i;
    batches += k;
  }
  EXPECT_GT(batches, n);
  EXPECT_GT(lanes, 10 * n);  // every particle has neighbours besides itself
}

// simd::at_packed2 reads field 0 and field 1 of the records at each lane's index, as gathers do.
TEST(SimdPacked, AtPacked2ReadsBothFieldsOfEachLanesRecord) {
  std::vector<float> rec(2 * 64);
  for (std::size_t i = 0; i < rec.size(); ++i) rec[i] = 0.5f * float(i) - 7.0f;
  const simd::i8 j = {63, 0, 17, 17, 5, 40, 2, 31};
  simd::f8 a, b;
  simd::at_packed2(rec.data(), j, a, b);
  for (int l = 0; l < simd::kWidth; ++l) {
    EXPECT_EQ(a[l], rec[2 * std::size_t(j[l])]) << "lane " << l;
    EXPECT_EQ(b[l], rec[2 * std::size_t(j[l]) + 1]) << "lane " << l;
  }
}

// Along a periodic axis a list holds the neighbours across the seam too: each particle's list is
// its brute-force neighbour set under the minimum image (|d| ≤ half the period along x), for
// 1 and 2 threads alike. About a fifth of the particles lie within a support of the seam.
template <int D>
__attribute__((noinline)) float periodic_dist2(const float* const xs[D], std::size_t i, std::size_t j, float period) {
  float r2 = 0;
  for (int a = 0; a < D; ++a) {
    float d = xs[a][i] - xs[a][j];
    if (a == 0) {
      d = d > 0.5f * period ? d - period : d;
      d = d < -0.5f * period ? d + period : d;
    }
    r2 += d * d;
  }
  return r2;
}

TYPED_TEST(GridTest, PeriodicNeighbourListsMatchTheMinimumImage) {
  constexpr int D = TypeParam::D;
  const float cell = 0.09f;
  const auto pts = uniform<D>(D == 2 ? 1500 : 3000, 0.0f, 1.0f, 41);
  const std::size_t n = pts.size();
  bool periodic[D] = {};
  periodic[0] = true;
  Built<D> b;
  build<D>(b, pts, vec<D>(0.0f), vec<D>(1.0f), cell, 1, periodic);
  const UniformGrid<D>& grid = b.grid;
  ASSERT_TRUE(grid.periodic(0));
  const float* const* ptr = b.ptr;
  NeighbourList<D> one, two;
  one.build(grid, ptr, n, cell * cell, ThreadPool(1));
  two.build(grid, ptr, n, cell * cell, ThreadPool(2));
  const float period = grid.period(0);
  ASSERT_GT(period, 0.0f);
  std::size_t across = 0;
  for (std::size_t i = 0; i < n; ++i) {
    std::vector<uint32_t> want;
    for (std::size_t j = 0; j < n; ++j)
      if (periodic_dist2<D>(ptr, i, j, period) < cell * cell) {
        want.push_back(uint32_t(j));
        if (std::abs(ptr[0][i] - ptr[0][j]) > 0.5f * period) ++across;
      }
    std::vector<uint32_t> got(one.begin(i), one.begin(i) + one.count(i));
    std::sort(got.begin(), got.end());
    ASSERT_EQ(got, want) << D << "D periodic, particle " << i;
    ASSERT_EQ(two.count(i), one.count(i));
    for (uint32_t s = 0; s < one.count(i); ++s) ASSERT_EQ(two.begin(i)[s], one.begin(i)[s]);
  }
  EXPECT_GT(across, n / 8) << "pairs across the seam";  // 3D: 750 for 3,000 particles
}

// mark_occupied_stencils: a walk from a cell whose stencil holds nothing is skipped, and that
// may lose no candidate. Samples in two thin "walls" (x < 0.1 and y < 0.1, as a container's
// wall samples lie), walked from query points all over the box (as fluid particles walk the
// wall grid), plain and periodic along x (the stencil wraps, so cells at the far end see the
// x < 0.1 wall), 1 and 2 threads.
TYPED_TEST(GridTest, WalksFromCellsWithNothingNearSkipNoCandidate) {
  constexpr int D = TypeParam::D;
  const float cell = 0.08f, support2 = cell * cell;
  Points<D> walls = uniform<D>(D == 2 ? 600 : 2000, 0.0f, 1.0f, 51);
  for (std::size_t i = 0; i < walls.size(); ++i) walls[i][i % 2] *= 0.1f;
  const Points<D> queries = uniform<D>(D == 2 ? 800 : 1500, 0.0f, 1.0f, 52);
  for (const bool wrap : {false, true}) {
    for (const int threads : {1, 2}) {
      const std::string what = std::to_string(D) + "D" + (wrap ? " periodic" : "") + ", " +
                               std::to_string(threads) + " threads";
      bool periodic[D] = {};
      periodic[0] = wrap;
      Built<D> b;
      build<D>(b, walls, vec<D>(0.0f), vec<D>(1.0f), cell, threads, periodic);
      UniformGrid<D>& grid = b.grid;
      const std::size_t n = walls.size();
      for (std::size_t c = 0; c < grid.cell_count(); ++c)
        ASSERT_FALSE(grid.stencil_empty(uint32_t(c))) << what << ": no table before marking";
      grid.mark_occupied_stencils();
      // The table says what the ranges say, interior cell by interior cell.
      std::size_t empty = 0, interior = 0;
      for (std::size_t c = 0; c < grid.cell_count(); ++c) {
        bool inside = true;
        std::size_t rest = c;
        for (int a = 0; a < D; ++a) {
          const int i = int(rest % std::size_t(grid.dim(a)));
          rest /= std::size_t(grid.dim(a));
          inside = inside && i >= 1 && i <= grid.dim(a) - 2;
        }
        if (!inside) continue;  // padding: no particle lies there, no walk starts there
        ++interior;
        std::size_t in_reach = 0;
        grid.for_each_range(uint32_t(c), [&](uint32_t lo, uint32_t hi) { in_reach += hi - lo; });
        ASSERT_EQ(grid.stencil_empty(uint32_t(c)), in_reach == 0) << what << ": cell " << c;
        empty += in_reach == 0;
      }
      EXPECT_GT(empty, interior / 3) << what << ": most cells are far from the walls";
      EXPECT_LT(empty, interior) << what;
      // Every query finds exactly its brute-force (minimum-image) candidates.
      std::size_t pairs = 0;
      for (const auto& q : queries) {
        float xi[D];
        Vec<D> p;
        for (int a = 0; a < D; ++a) p[a] = xi[a] = q[a];
        std::vector<uint32_t> want, got;
        for (std::size_t j = 0; j < n; ++j) {
          float r2 = 0;
          for (int a = 0; a < D; ++a) {
            float d = xi[a] - b.ptr[a][j];
            if (wrap && a == 0) {
              d = d > 0.5f * grid.period(0) ? d - grid.period(0) : d;
              d = d < -0.5f * grid.period(0) ? d + grid.period(0) : d;
            }
            r2 += d * d;
          }
          if (r2 < support2) want.push_back(uint32_t(j));
        }
        auto collect = [&](uint32_t j, const simd::f8*, simd::f8, simd::i8 m) {
          for (int l = 0; l < simd::kWidth; ++l)
            if (m[l]) got.push_back(j + uint32_t(l));
        };
        if (wrap)
          for_each_candidate_batch<D, true>(grid, grid.cell_of(p), b.ptr, xi, support2, collect);
        else
          for_each_candidate_batch<D, false>(grid, grid.cell_of(p), b.ptr, xi, support2, collect);
        std::sort(got.begin(), got.end());
        ASSERT_EQ(got, want) << what << ": query at cell " << grid.cell_of(p);
        pairs += want.size();
      }
      EXPECT_GT(pairs, queries.size() / 4) << what << ": queries near the walls find samples";
      // A new build drops the table: its cells would describe the old samples.
      build<D>(b, queries, vec<D>(0.0f), vec<D>(1.0f), cell, threads, periodic);
      for (std::size_t c = 0; c < grid.cell_count(); ++c)
        ASSERT_FALSE(grid.stencil_empty(uint32_t(c))) << what << ": table kept after a build";
    }
  }
}

// ---- the padding the batches read -----------------------------------------------------------

/// Lanes past a range's end read the kPad elements past the array's size, and sums weight them by
/// zero; 0 × NaN is NaN, so those elements must be zero whatever the array held before: after a
/// shrink too (session 38: scratch that had carried int -1s, a NaN's bits, was swapped in shorter).
TEST(AlignedArrayPad, ShrinkingLeavesThePadZero) {
  AlignedArray<float> a(100);
  for (std::size_t i = 0; i < a.size(); ++i) a[i] = std::numeric_limits<float>::quiet_NaN();
  a.resize(40);
  for (std::size_t i = 40; i < 40 + AlignedArray<float>::kPad; ++i) EXPECT_EQ(a.data()[i], 0.0f) << i;
  a.resize(30);  // and again, from a size whose pad is already clear
  for (std::size_t i = 30; i < 30 + AlignedArray<float>::kPad; ++i) EXPECT_EQ(a.data()[i], 0.0f) << i;
  a.resize(60);  // growing back: the new elements are zero too
  for (std::size_t i = 30; i < 60 + AlignedArray<float>::kPad; ++i) EXPECT_EQ(a.data()[i], 0.0f) << i;
  for (std::size_t i = 0; i < 30; ++i) EXPECT_TRUE(std::isnan(a[i])) << i;  // the kept ones keep their values
}

}  // namespace
}  // namespace rtsph::grid_test
