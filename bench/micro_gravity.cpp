// Micro-benchmarks of self-gravity (src/core/gravity_direct.h, gravity_tree.h): direct
// summation and the Barnes-Hut octree (build + walk, θ = 0.5, quadrupoles) on a Plummer sphere
// of N particles with h following the local spacing, 1 and 2 threads. Counters: interactions
// per particle for the tree (multipoles, particle pairs) and the build alone.
//   rtsph_microbench --benchmark_filter=Gravity
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <map>
#include <random>
#include <vector>

#include "core/gravity_direct.h"
#include "core/gravity_tree.h"
#include "core/parallel.h"

namespace rtsph {
namespace {

// Plummer sphere, scale radius 1, total mass 1, truncated at 20; h ∝ ρ^(-1/3) with ~50
// neighbours inside 2h, as adaptive SPH would set it: the central number density is
// 3n/(4π), so (4/3)π(2h₀)³ · 3n/(4π) = 50 gives h₀ = ½ (50/n)^(1/3).
struct Plummer {
  std::vector<float> x[3], m, h, a[3], pot;
  explicit Plummer(std::size_t n) {
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::normal_distribution<double> g;
    const double h0 = 0.5 * std::cbrt(50.0 / double(n));
    while (m.size() < n) {
      const double r = 1.0 / std::sqrt(std::pow(u(rng), -2.0 / 3.0) - 1.0);
      if (!(r < 20)) continue;
      double p[3], n2 = 0;
      for (double& c : p) {
        c = g(rng);
        n2 += c * c;
      }
      for (int k = 0; k < 3; ++k) x[k].push_back(float(p[k] * r / std::sqrt(n2)));
      m.push_back(float(1.0 / double(n)));
      h.push_back(float(h0 * std::pow(1 + r * r, 5.0 / 6.0)));
    }
    for (auto& v : a) v.resize(n);
    pot.resize(n);
  }
  GravitySources<3> sources() const {
    GravitySources<3> s;
    for (int k = 0; k < 3; ++k) s.x[k] = x[k].data();
    s.m = m.data();
    s.h = h.data();
    s.n = m.size();
    return s;
  }
  float* acc[3];
  float* const* out() {
    for (int k = 0; k < 3; ++k) acc[k] = a[k].data();
    return acc;
  }
};

Plummer& cloud(std::size_t n) {
  static std::map<std::size_t, Plummer> clouds;
  auto it = clouds.find(n);
  if (it == clouds.end()) it = clouds.emplace(n, Plummer(n)).first;
  return it->second;
}

// Args: particles, threads.
void BM_GravityDirect(benchmark::State& state) {
  Plummer& c = cloud(std::size_t(state.range(0)));
  const ThreadPool pool(int(state.range(1)));
  for (auto _ : state) {
    gravity_direct<3>(c.sources(), 1.0, c.out(), nullptr, pool);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * state.range(0));
}

// One self-gravity step with the tree: build (keys, sort, nodes, moments) and walk.
void BM_GravityTree(benchmark::State& state) {
  Plummer& c = cloud(std::size_t(state.range(0)));
  const ThreadPool pool(int(state.range(1)));
  GravityTree tree;
  for (auto _ : state) {
    tree.build(c.sources(), pool);
    tree.accelerations(1.0, 0.5, c.out(), nullptr, pool);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * state.range(0));
  state.counters["nodes_per_particle"] = tree.mean_node_interactions();
  state.counters["pairs_per_particle"] = tree.mean_particle_interactions();
}

void BM_GravityTreeBuild(benchmark::State& state) {
  Plummer& c = cloud(std::size_t(state.range(0)));
  const ThreadPool pool(int(state.range(1)));
  GravityTree tree;
  for (auto _ : state) {
    tree.build(c.sources(), pool);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * state.range(0));
  state.counters["tree_nodes"] = double(tree.node_count());
}

BENCHMARK(BM_GravityDirect)->Args({10000, 1})->Args({10000, 2})->Args({100000, 2})
    ->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_GravityTree)->Args({10000, 1})->Args({10000, 2})->Args({100000, 2})
    ->Args({1000000, 2})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_GravityTreeBuild)->Args({100000, 2})->Args({1000000, 2})
    ->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace rtsph
