#pragma once
// Uniform-grid neighbour search (Green 2008; Ihmsen et al. 2011 "A parallel SPH implementation
// on multi-core CPUs"). Cell edge = kernel support, linear cell keys with x fastest, and a
// stable counting sort. After the caller reorders its arrays by order(), the particles of each
// cell are contiguous and, because x is fastest, the three cells of a row along x form one
// contiguous range: a particle's candidates are 3^(D-1) ranges (9 in 3D, 3 in 2D).
// A layer of empty padding cells surrounds the grid, so stencils never leave it.
#include <cstdint>
#include <cstddef>

#include "core/aligned_array.h"
#include "core/parallel.h"
#include "core/vec.h"

namespace rtsph {

template <int D>
class UniformGrid {
 public:
  /// Covers [lo, hi] with cells of edge `cell`. Points outside are clamped to the edge cells.
  void configure(const Vec<D>& lo, const Vec<D>& hi, Real cell);

  std::size_t cell_count() const { return cells_; }
  Real cell_size() const { return cell_; }
  const Vec<D>& origin() const { return origin_; }
  int dim(int axis) const { return dims_[axis]; }

  uint32_t cell_of(const Vec<D>& p) const;

  /// Sorts particles by cell. xs[k] is the k-th coordinate array. Afterwards order()[new] = old,
  /// and cell_start()/sorted_cells() describe the particles in the new order.
  void build(const Real* const xs[D], std::size_t n, const ThreadPool& pool);

  const uint32_t* order() const { return order_.data(); }
  const uint32_t* cell_start() const { return start_.data(); }
  /// Cell key of each particle, in sorted order.
  const uint32_t* sorted_cells() const { return keys_sorted_.data(); }
  std::size_t particle_count() const { return n_; }
  std::size_t bytes() const {
    return order_.bytes() + start_.bytes() + keys_.bytes() + keys_sorted_.bytes();
  }

  /// Calls fn(begin, end) for each contiguous candidate range around `cell`.
  template <class Fn>
  void for_each_range(uint32_t cell, Fn&& fn) const {
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

 private:
  Vec<D> origin_{};
  Real cell_ = 1;
  double inv_cell_ = 1;
  int dims_[D]{};
  std::size_t cells_ = 0, n_ = 0;
  AlignedArray<uint32_t> keys_, keys_sorted_, order_, start_;
};

}  // namespace rtsph
