#pragma once
// What the grid tests share (core_grid_test.cpp, core_pair_batch_test.cpp): a brute-force
// reference, grids built from point sets, and the structural and neighbour-set checks.
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

namespace rtsph::grid_test {


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
inline int failures() {
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
           int threads, const bool* periodic = nullptr) {
  const std::size_t n = pts.size();
  std::vector<float> in[D];
  const float* inp[D];
  for (int a = 0; a < D; ++a) {
    in[a].resize(n);
    for (std::size_t i = 0; i < n; ++i) in[a][i] = pts[i][a];
    inp[a] = in[a].data();
  }
  b.grid.configure(lo, hi, cell, periodic);
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

/// The half stencil (for_each_forward_range): every pair within the support is visited exactly
/// once, from its lower sorted index, and a particle in layer L reaches layers L and L + 1 only
/// (what FluidWorld's two-phase schedule relies on to write to partners without races).
template <int D>
void check_forward(const Built<D>& b, std::size_t n, float cell, const std::string& what) {
  const float support2 = cell * cell;
  const auto& g = b.grid;
  // The layers partition the particles in order.
  ASSERT_EQ(g.layer_start(0), 0u) << what;
  ASSERT_EQ(g.layer_start(g.layer_count()), n) << what;
  std::vector<int> layer(n, -1);
  for (int l = 0; l < g.layer_count(); ++l) {
    ASSERT_LE(g.layer_start(l), g.layer_start(l + 1)) << what;
    for (uint32_t i = g.layer_start(l); i < g.layer_start(l + 1); ++i) layer[i] = l;
  }
  std::size_t brute = 0, found = 0;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      if (dist2<D>(b.ptr, i, j) < support2) ++brute;
  std::vector<uint32_t> stamp(n, UINT32_MAX);
  for (std::size_t i = 0; i < n; ++i) {
    g.for_each_forward_range(g.sorted_cells()[i], uint32_t(i) + 1, [&](uint32_t begin, uint32_t end) {
      ASSERT_LE(begin, end) << what;
      ASSERT_LE(end, n) << what;
      for (uint32_t j = begin; j < end; ++j) {
        ASSERT_GT(j, i) << what << ": the forward walk of " << i << " reaches back to " << j;
        ASSERT_TRUE(layer[j] == layer[i] || layer[j] == layer[i] + 1)
            << what << ": " << i << " in layer " << layer[i] << " reaches layer " << layer[j];
        if (!(dist2<D>(b.ptr, i, j) < support2)) continue;
        ASSERT_NE(stamp[j], uint32_t(i)) << what << ": pair " << i << ", " << j << " visited twice";
        stamp[j] = uint32_t(i);
        ++found;
      }
    });
    if (::testing::Test::HasFatalFailure()) return;
  }
  // Each found pair is a neighbour pair (j > i, within the support, once), so equal counts mean
  // the forward walk finds them all.
  EXPECT_EQ(found, brute) << what << ": the forward walk finds " << found << " of " << brute << " pairs";
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
  check_forward(one, n, cell, what);
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

}  // namespace rtsph::grid_test
