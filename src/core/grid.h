#pragma once
// Uniform-grid neighbour search (Green 2008; Ihmsen et al. 2011 "A parallel SPH implementation
// on multi-core CPUs"). Cell edge = kernel support, linear cell keys with x fastest, and a
// stable counting sort. After the caller reorders its arrays by order(), the particles of each
// cell are contiguous and, because x is fastest, the three cells of a row along x form one
// contiguous range: a particle's candidates are 3^(D-1) ranges (9 in 3D, 3 in 2D).
// A layer of empty padding cells surrounds the grid, so stencils never leave it.
//
// Periodic axes: the interior cells tile the period exactly (cell edge = period / n ≥ the
// support, n ≥ 3), a stencil that reaches past the seam continues on the far side (the row
// along x is then split into separate ranges), and distances use the minimum image
// (wrap_offset), so a pair across the seam is a pair like any other.
#include <cstdint>
#include <cstddef>
#include <algorithm>
#include <cmath>

#include "core/aligned_array.h"
#include "core/parallel.h"
#include "core/vec.h"

namespace rtsph {

template <int D>
class UniformGrid {
 public:
  /// Covers [lo, hi] with cells of edge `cell` (at least). Points outside are clamped to the
  /// edge cells, except along axes with periodic[a]: there [lo, hi) is one period, points wrap,
  /// and it must hold at least three cells (else std::invalid_argument).
  void configure(const Vec<D>& lo, const Vec<D>& hi, Real cell, const bool* periodic = nullptr);

  std::size_t cell_count() const { return cells_; }
  /// Cell edge along `axis` (the support, a little more along a periodic axis).
  Real cell_size(int axis = 0) const { return cell_[axis]; }
  bool periodic(int axis) const { return period_[axis] > 0; }
  bool any_periodic() const { return any_periodic_; }
  /// Period along `axis` (m), 0 when the axis is not periodic.
  Real period(int axis) const { return period_[axis]; }
  const Vec<D>& origin() const { return origin_; }
  int dim(int axis) const { return dims_[axis]; }
  /// 1 / cell edge along `axis`, in double: cell_of's arithmetic (the GPU backend repeats it).
  double inv_cell(int axis) const { return inv_cell_[axis]; }

  /// The cell holding p (clamped to the interior cells; wrapped along periodic axes). Inline:
  /// the force sum calls it once per particle.
  [[gnu::always_inline]] uint32_t cell_of(const Vec<D>& p) const {
    uint32_t key = 0, stride = 1;
    for (int a = 0; a < D; ++a) {
      double f = (double(p[a]) - double(origin_[a])) * inv_cell_[a];
      if (period_[a] > 0) {
        // Wrap into the period's cells 1..n (a point slightly outside after a correction).
        const double n = double(dims_[a] - 2);
        f = 1.0 + (f - 1.0) - n * std::floor((f - 1.0) / n);
      }
      // The comparison form also sends NaN to the edge cell instead of undefined behaviour.
      const int c = f >= 1.0 ? (f < double(dims_[a] - 1) ? int(f) : dims_[a] - 2) : 1;
      key += uint32_t(c) * stride;
      stride *= uint32_t(dims_[a]);
    }
    return key;
  }

  /// Sorts particles by cell. xs[k] is the k-th coordinate array. Afterwards order()[new] = old,
  /// and cell_start()/sorted_cells() describe the particles in the new order.
  void build(const Real* const xs[D], std::size_t n, const ThreadPool& pool);

  /// After build(): notes, per interior cell, whether any particle lies in its stencil's
  /// ranges. Walks from a cell with none (for_each_candidate_batch) then skip the 3^(D-1) range
  /// lookups: most fluid particles have no wall sample within reach, and every pair sum walks
  /// the wall grid. Costs a clear of the table and 3^D marks per occupied cell (the wall grid
  /// is rebuilt every step where obstacles move). The next build() drops the table.
  void mark_occupied_stencils();
  /// True only when the table is current and interior `cell`'s stencil holds no particle (the
  /// padding cells, where no particle lies, are not described).
  bool stencil_empty(uint32_t cell) const { return occupancy_current_ && occupied_[cell] == 0; }

  const uint32_t* order() const { return order_.data(); }
  const uint32_t* cell_start() const { return start_.data(); }
  /// Cell key of each particle, in sorted order.
  const uint32_t* sorted_cells() const { return keys_sorted_.data(); }
  std::size_t particle_count() const { return n_; }
  std::size_t bytes() const {
    return order_.bytes() + start_.bytes() + keys_.bytes() + keys_sorted_.bytes() + occupied_.bytes();
  }

  /// The minimum image of the offsets d (x_i − x_j) along periodic axes: |d| ≤ period/2. Any
  /// two points of the domain are less than 1.5 periods apart, so one shift suffices.
  template <class V>
  [[gnu::always_inline]] void wrap_offsets(V* d) const {
    for (int k = 0; k < D; ++k) {
      if (period_[k] <= 0) continue;
      const Real L = period_[k], half = Real(0.5) * period_[k];
      d[k] = d[k] > half ? d[k] - L : d[k];
      d[k] = d[k] < -half ? d[k] + L : d[k];
    }
  }

  /// Calls fn(begin, end) for each contiguous candidate range around `cell`, on any grid.
  template <class Fn>
  void for_each_range(uint32_t cell, Fn&& fn) const {
    if (any_periodic_)
      for_each_periodic_range(cell, fn);
    else
      for_each_flat_range(cell, fn);
  }
  /// The same on a grid without periodic axes: the 3^(D-1) rows of the stencil, each three cells
  /// along x in one range. The hot pair walks call this or the periodic one by a template flag
  /// chosen once per sum (pair_loop.h): a choice per particle cost 11% of a WCSPH step.
  template <class Fn>
  void for_each_flat_range(uint32_t cell, Fn&& fn) const {
    const uint32_t* s = start_.data();
    if constexpr (D == 2) {
      for (int dy = -1; dy <= 1; ++dy) {
        const uint32_t k = cell + dy * dims_[0] - 1;
        fn(s[k], s[k + 3]);
      }
    } else {
      const int slab = dims_[0] * dims_[1];
      for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy) {
          const uint32_t k = cell + dz * slab + dy * dims_[0] - 1;
          fn(s[k], s[k + 3]);
        }
    }
  }
  /// The forward half of the stencil on a grid without periodic axes, for sums that visit each
  /// pair once and add to both particles: the rows ahead of the particle's own (+y, then the
  /// three rows at +z in 3D) whole, and its own row from sorted index `first` on (pass i + 1).
  /// Every pair of particles within one cell of each other is then visited from exactly one
  /// of them, and always from the lower sorted index: writes go forward only.
  template <class Fn>
  void for_each_forward_range(uint32_t cell, uint32_t first, Fn&& fn) const {
    const uint32_t* s = start_.data();
    const uint32_t own = cell - 1;
    if (s[own + 3] > first) fn(std::max(first, s[own]), s[own + 3]);
    const uint32_t up = own + uint32_t(dims_[0]);
    fn(s[up], s[up + 3]);
    if constexpr (D == 3) {
      const uint32_t slab = uint32_t(dims_[0]) * uint32_t(dims_[1]);
      for (int dy = -1; dy <= 1; ++dy) {
        const uint32_t k = uint32_t(int(own + slab) + dy * dims_[0]);
        fn(s[k], s[k + 3]);
      }
    }
  }
  /// Layers of cells across the slowest axis (z in 3D, y in 2D), padding included: layer L
  /// holds the sorted particles [layer_start(L), layer_start(L + 1)). The forward stencil of a
  /// particle in layer L reaches layers L and L + 1 only.
  int layer_count() const { return dims_[D - 1]; }
  uint32_t layer_start(int layer) const {
    std::size_t cells_per_layer = 1;
    for (int a = 0; a < D - 1; ++a) cells_per_layer *= std::size_t(dims_[a]);
    return start_[std::size_t(layer) * cells_per_layer];
  }
  /// The stencil with wrapping: rows along y/z continue past the seam, and the row along x is
  // one range when it does not cross the seam, else one range per cell.
  template <class Fn>
  void for_each_periodic_range(uint32_t cell, Fn&& fn) const {
    const uint32_t* s = start_.data();
    int c[3] = {0, 0, 0};
    coordinates(cell, c);
    const bool split_x = period_[0] > 0 && (c[0] == 1 || c[0] == dims_[0] - 2);
    const int dz_lo = D == 3 ? -1 : 0, dz_hi = D == 3 ? 1 : 0;
    for (int dz = dz_lo; dz <= dz_hi; ++dz)
      for (int dy = -1; dy <= 1; ++dy) {
        const int y = wrap(1, c[1] + dy);
        const int z = D == 3 ? wrap(2, c[2] + dz) : 0;
        const uint32_t row = uint32_t(z) * uint32_t(dims_[1]) * uint32_t(dims_[0]) + uint32_t(y) * uint32_t(dims_[0]);
        if (!split_x) {
          const uint32_t k = row + uint32_t(c[0] - 1);
          fn(s[k], s[k + 3]);
        } else {
          for (int dx = -1; dx <= 1; ++dx) {
            const uint32_t k = row + uint32_t(wrap(0, c[0] + dx));
            fn(s[k], s[k + 1]);
          }
        }
      }
  }

 private:
  /// The cell's coordinate along each axis (padding included: interior cells are 1..dims-2).
  void coordinates(uint32_t cell, int c[3]) const {
    for (int a = 0; a < D; ++a) {
      c[a] = int(cell % uint32_t(dims_[a]));
      cell /= uint32_t(dims_[a]);
    }
  }
  /// A neighbour's coordinate v along `axis`, continued past the seam of a periodic axis.
  int wrap(int axis, int v) const {
    if (period_[axis] <= 0) return v;
    const int n = dims_[axis] - 2;
    return v < 1 ? v + n : v > n ? v - n : v;
  }

  Vec<D> origin_{};
  Real cell_[D]{};
  double inv_cell_[D]{};
  Real period_[D]{};
  bool any_periodic_ = false;
  int dims_[D]{};
  std::size_t cells_ = 0, n_ = 0;
  AlignedArray<uint32_t> keys_, keys_sorted_, order_, start_;
  AlignedArray<uint8_t> occupied_;  // mark_occupied_stencils()
  bool occupancy_current_ = false;
};

}  // namespace rtsph
