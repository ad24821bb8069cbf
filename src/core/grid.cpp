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
void UniformGrid<D>::build(const Real* const xs[D], std::size_t n, const ThreadPool& pool) {
  n_ = n;
  occupancy_current_ = false;
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

template <int D>
void UniformGrid<D>::mark_occupied_stencils(const ThreadPool& pool) {
  occupied_.resize(cells_);
  uint8_t* out = occupied_.data();
  pool.parallel_for(cells_, [&](std::size_t b, std::size_t e) {
    for (std::size_t c = b; c < e; ++c) {
      // Padding cells count as occupied: their stencils would leave the grid, and no walk
      // starts there (cell_of clamps to the interior).
      bool interior = true;
      std::size_t rest = c;
      for (int a = 0; a < D; ++a) {
        const int i = int(rest % std::size_t(dims_[a]));
        rest /= std::size_t(dims_[a]);
        interior = interior && i >= 1 && i <= dims_[a] - 2;
      }
      bool any = !interior;
      if (interior)
        for_each_range(uint32_t(c), [&](uint32_t lo, uint32_t hi) { any = any || hi > lo; });
      out[c] = any ? 1 : 0;
    }
  });
  occupancy_current_ = true;
}

template class UniformGrid<2>;
template class UniformGrid<3>;

}  // namespace rtsph
