#pragma once
// The inner loop every SPH sum shares: for particle i, visit the candidates of its 3^(D-1)
// contiguous cell ranges eight at a time. fn(j, d, r2, mask) gets lanes j..j+7, the offsets
// d[k] = x_i - x_j, the squared distances, and a mask of lanes that are in range and inside the
// kernel support. Lanes past a range end read the array's padding and are masked off. Along
// periodic axes d is the minimum image.
#include "core/grid.h"
#include "core/simd.h"

namespace rtsph {

// Forced inlining keeps the caller's accumulators in registers across batches.
template <int D, class Fn>
[[gnu::always_inline]] inline void for_each_candidate_batch(const UniformGrid<D>& grid, uint32_t cell,
                                     const Real* const xs[D], const Real xi[D], Real support2,
                                     Fn&& fn) {
  using simd::f8;
  using simd::i8;
  grid.for_each_range(cell, [&](uint32_t begin, uint32_t end) {
    for (uint32_t j = begin; j < end; j += simd::kWidth) {
      f8 d[D];
      for (int k = 0; k < D; ++k) d[k] = xi[k] - simd::load(xs[k] + j);
      if (grid.any_periodic()) grid.wrap_offsets(d);  // minimum image across a seam
      f8 r2 = f8{};
      for (int k = 0; k < D; ++k) r2 += d[k] * d[k];
      const i8 in_range = simd::lane_index() < int(end - j);
      const i8 mask = in_range & (r2 < support2);
      if (simd::any(mask)) fn(j, d, r2, mask);
    }
  });
}

}  // namespace rtsph
