#include "core/grid.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rtsph {

template <int D>
void UniformGrid<D>::configure(const Vec<D>& lo, const Vec<D>& hi, Real cell, const bool* periodic) {
  // A cell a few ulps wider than the support, and cell indices in double: otherwise float
  // rounding can put two particles closer than the support into cells two apart.
  const Real edge = cell * Real(1 + 1e-5);
  std::size_t cells = 1;
  any_periodic_ = false;
  for (int a = 0; a < D; ++a) {
    // +2 padding cells so the stencil of any clamped particle stays inside the grid.
    const double span = std::max(0.0, double(hi[a]) - double(lo[a]));
    double interior = std::max(1.0, std::ceil(span / double(edge) + 1e-6));
    cell_[a] = edge;
    period_[a] = 0;
    if (periodic && periodic[a]) {
      // Whole cells per period, each at least the support: the stencil then covers every
      // image within reach, and three distinct cells per row keep a pair from being seen twice.
      interior = std::floor(span / double(edge));
      if (interior < 3)
        throw std::invalid_argument("a periodic axis must be at least three kernel supports long");
      cell_[a] = Real(span / interior);
      period_[a] = Real(span);
      any_periodic_ = true;
    }
    if (interior > 1e7) throw std::length_error("neighbour grid too large");
    inv_cell_[a] = 1.0 / double(cell_[a]);
    dims_[a] = int(interior) + 2;
    origin_[a] = lo[a] - cell_[a];
    cells *= std::size_t(dims_[a]);
  }
  if (cells >= (std::size_t(1) << 31)) throw std::length_error("neighbour grid too large");
  cells_ = cells;
  start_.resize(cells_ + 1);
}

template <int D>
uint32_t UniformGrid<D>::cell_of(const Vec<D>& p) const {
  uint32_t key = 0, stride = 1;
  for (int a = 0; a < D; ++a) {
    double f = (double(p[a]) - double(origin_[a])) * inv_cell_[a];
    if (period_[a] > 0) {
      // Wrap into the period's cells 1..n (a point slightly outside after a correction).
      const double n = double(dims_[a] - 2);
      f = 1.0 + (f - 1.0) - n * std::floor((f - 1.0) / n);
    }
    // The comparison form also sends NaN to the edge cell instead of undefined behaviour.
    int c = f >= 1.0 ? (f < double(dims_[a] - 1) ? int(f) : dims_[a] - 2) : 1;
    key += uint32_t(c) * stride;
    stride *= uint32_t(dims_[a]);
  }
  return key;
}

template <int D>
void UniformGrid<D>::build(const Real* const xs[D], std::size_t n, const ThreadPool& pool) {
  n_ = n;
  keys_.resize(n);
  keys_sorted_.resize(n);
  order_.resize(n);
  pool.parallel_for(n, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      Vec<D> p;
      for (int a = 0; a < D; ++a) p[a] = xs[a][i];
      keys_[i] = cell_of(p);
    }
  });
  // Stable counting sort: histogram, exclusive prefix sum, scatter in input order.
  uint32_t* s = start_.data();
  std::fill(s, s + cells_ + 1, 0u);
  for (std::size_t i = 0; i < n; ++i) ++s[keys_[i] + 1];
  for (std::size_t c = 0; c < cells_; ++c) s[c + 1] += s[c];
  // s[c] is now the first slot of cell c; scatter using s as cursors, then shift back.
  for (std::size_t i = 0; i < n; ++i) {
    const uint32_t slot = s[keys_[i]]++;
    order_[slot] = uint32_t(i);
    keys_sorted_[slot] = keys_[i];
  }
  for (std::size_t c = cells_; c > 0; --c) s[c] = s[c - 1];
  s[0] = 0;
}

template class UniformGrid<2>;
template class UniformGrid<3>;

}  // namespace rtsph
