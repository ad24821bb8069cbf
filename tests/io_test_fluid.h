#pragma once
// Synthetic fluid particles shared by the exporter tests.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

#include "core/particles.h"

namespace rtsph::test {

/// Random particles: mostly ordinary values, some arbitrary finite bit patterns (denormals,
/// huge, negative zero) that stress round-tripping. Ids are a shuffled, optionally sparse range.
struct Fluid {
  int dim;
  std::vector<float> x[3], v[3], rho, p;
  std::vector<std::uint32_t> id;

  Fluid(int d, std::size_t n, std::uint32_t id_stride, unsigned seed) : dim(d) {
    std::mt19937 g(seed);
    auto value = [&g]() {
      if (g() % 4) return std::uniform_real_distribution<float>(-10.f, 10.f)(g);
      float f;
      do f = std::bit_cast<float>(static_cast<std::uint32_t>(g())); while (!std::isfinite(f));
      return f;
    };
    for (int k = 0; k < d; ++k) {
      for (std::size_t i = 0; i < n; ++i) x[k].push_back(value()), v[k].push_back(value());
    }
    for (std::size_t i = 0; i < n; ++i) rho.push_back(value()), p.push_back(value()), id.push_back(i * id_stride + 5);
    std::shuffle(id.begin(), id.end(), g);
  }
  rtsph::ParticleView view() const {
    rtsph::ParticleView w;
    w.dim = dim;
    w.count = id.size();
    for (int k = 0; k < dim; ++k) w.x[k] = x[k].data(), w.v[k] = v[k].data();
    w.density = rho.data();
    w.pressure = p.data();
    w.id = id.data();
    return w;
  }
  std::vector<std::size_t> by_id() const {
    std::vector<std::size_t> order(id.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](auto a, auto b) { return id[a] < id[b]; });
    return order;
  }
};

}  // namespace rtsph::test
