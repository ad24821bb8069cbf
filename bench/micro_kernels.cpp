// Micro-benchmarks of the neighbour search core: grid build (keys + stable counting sort) at 64k
// particles, and the SPH density sum through for_each_candidate_batch (8-lane candidate loop),
// 2D and 3D, 1 and 2 threads. Particles sit on a jittered lattice of spacing dx with h = 1.2 dx
// and cubic-spline support 2h, the usual SPH resolution (~20 neighbours in 2D, ~60 in 3D; the
// neighbours/candidates counters report the measured values, mean_rho ≈ 1/dx^D checks the sum).
//   rtsph_microbench --benchmark_filter=GridBuild
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "core/aligned_array.h"
#include "core/grid.h"
#include "core/kernels.h"
#include "core/pair_loop.h"
#include "core/parallel.h"

namespace rtsph {
namespace {

constexpr std::size_t kParticles = 1 << 16;  // 64k

template <int D>
struct Cloud {
  AlignedArray<float> x[D];
  const float* ptr[D];
  Vec<D> lo, hi;
  float dx, h, support;
  std::size_t n;

  Cloud() {
    const int side = int(std::ceil(std::pow(double(kParticles), 1.0 / D)));
    n = kParticles;
    dx = 0.01f;
    h = 1.2f * dx;
    support = 2 * h;
    std::mt19937 rng(42);
    std::uniform_real_distribution<float> jitter(-0.1f * dx, 0.1f * dx);
    for (int a = 0; a < D; ++a) x[a].resize(n);
    // Shuffled lattice order, so build() does real sorting work.
    std::vector<uint32_t> perm(n);
    for (std::size_t i = 0; i < n; ++i) perm[i] = uint32_t(i);
    std::shuffle(perm.begin(), perm.end(), rng);
    for (std::size_t i = 0; i < n; ++i) {
      std::size_t k = perm[i];
      for (int a = 0; a < D; ++a) {
        x[a][i] = (float(k % side) + 0.5f) * dx + jitter(rng);
        k /= side;
      }
    }
    for (int a = 0; a < D; ++a) {
      ptr[a] = x[a].data();
      lo[a] = 0;
      hi[a] = float(side) * dx;
    }
  }
};

template <int D>
const Cloud<D>& cloud() {
  static const Cloud<D> c;
  return c;
}

template <int D>
void BM_GridBuild(benchmark::State& state) {
  const auto& c = cloud<D>();
  const ThreadPool pool(int(state.range(0)));
  UniformGrid<D> grid;
  grid.configure(c.lo, c.hi, c.support);
  for (auto _ : state) {
    grid.build(c.ptr, c.n, pool);
    benchmark::DoNotOptimize(grid.order());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(c.n));
  state.counters["cells"] = double(grid.cell_count());
}

/// Sorted copy of the cloud plus its grid, as the solver has it after reordering.
template <int D>
struct Sorted {
  UniformGrid<D> grid;
  AlignedArray<float> x[D];
  const float* ptr[D];
  explicit Sorted(const Cloud<D>& c) {
    grid.configure(c.lo, c.hi, c.support);
    grid.build(c.ptr, c.n, ThreadPool(1));
    for (int a = 0; a < D; ++a) {
      x[a].resize(c.n);
      for (std::size_t i = 0; i < c.n; ++i) x[a][i] = c.x[a][grid.order()[i]];
      ptr[a] = x[a].data();
    }
  }
};

template <int D>
void BM_DensityPairLoop(benchmark::State& state) {
  using simd::f8;
  using simd::i8;
  const auto& c = cloud<D>();
  static const Sorted<D> s(c);
  const ThreadPool pool(int(state.range(0)));
  const CubicSpline<D> K(c.h);
  const float support2 = c.support * c.support, mass = 1.0f;
  AlignedArray<float> rho(c.n);
  const uint32_t* cells = s.grid.sorted_cells();
  for (auto _ : state) {
    pool.parallel_for(c.n, [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i) {
        float xi[D];
        for (int a = 0; a < D; ++a) xi[a] = s.ptr[a][i];
        f8 w{};
        for_each_candidate_batch<D, false>(s.grid, cells[i], s.ptr, xi, support2,
                                    [&](uint32_t, const f8*, f8 r2, i8 m) {
                                      w += simd::select(m, K.value(r2), f8{});
                                    });
        rho[i] = mass * simd::hsum(w);
      }
    });
    benchmark::DoNotOptimize(rho.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(c.n));
  // Neighbours per particle (in support) and candidates per particle (lanes loaded), once.
  std::size_t nb = 0, cand = 0;
  for (std::size_t i = 0; i < c.n; ++i) {
    float xi[D];
    for (int a = 0; a < D; ++a) xi[a] = s.ptr[a][i];
    for_each_candidate_batch<D, false>(s.grid, cells[i], s.ptr, xi, support2,
                                [&](uint32_t, const f8*, f8, i8 m) {
                                  for (int l = 0; l < simd::kWidth; ++l) nb += m[l] != 0;
                                });
    s.grid.for_each_range(cells[i], [&](uint32_t b, uint32_t e) { cand += e - b; });
  }
  state.counters["neighbours"] = double(nb) / double(c.n);
  state.counters["candidates"] = double(cand) / double(c.n);
  state.counters["mean_rho"] = [&] {
    double m = 0;
    for (std::size_t i = 0; i < c.n; ++i) m += rho[i];
    return m / double(c.n);
  }();
}

BENCHMARK(BM_GridBuild<2>)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond)->UseRealTime();
BENCHMARK(BM_GridBuild<3>)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond)->UseRealTime();
BENCHMARK(BM_DensityPairLoop<2>)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_DensityPairLoop<3>)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace rtsph
