#include "core/grid.h"

#include <algorithm>
#include <cmath>
#include <cstring>
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
void UniformGrid<D>::mark_occupied_stencils() {
  // A cell's stencil holds a particle exactly when one of its 3^D neighbours does (the
  // neighbourhood is symmetric, wrapped along periodic axes as for_each_range wraps it), so the
  // table is the occupied cells dilated by one: work in the occupied cells, not in the grid,
  // which matters where obstacles move and the wall grid is rebuilt every step.
  occupied_.resize(cells_);
  uint8_t* out = occupied_.data();
  std::memset(out, 0, cells_);
  const uint32_t* key = keys_sorted_.data();
  const int lo_z = D == 3 ? -1 : 0, hi_z = D == 3 ? 1 : 0;
  for (std::size_t i = 0; i < n_; ++i) {
    if (i > 0 && key[i] == key[i - 1]) continue;  // sorted: one visit per occupied cell
    int c[3] = {0, 0, 0};
    coordinates(key[i], c);
    for (int dz = lo_z; dz <= hi_z; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          std::size_t k = std::size_t(wrap(0, c[0] + dx)) + std::size_t(wrap(1, c[1] + dy)) * std::size_t(dims_[0]);
          if constexpr (D == 3) k += std::size_t(wrap(2, c[2] + dz)) * std::size_t(dims_[0]) * std::size_t(dims_[1]);
          out[k] = 1;
        }
  }
  occupancy_current_ = true;
}

template class UniformGrid<2>;
template class UniformGrid<3>;

}  // namespace rtsph
