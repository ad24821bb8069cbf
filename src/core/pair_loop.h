#pragma once
// The inner loop every SPH sum shares: for particle i, visit the candidates of its 3^(D-1)
// contiguous cell ranges eight at a time. fn(j, d, r2, mask) gets lanes j..j+7, the offsets
// d[k] = x_i - x_j, the squared distances, and a mask of lanes that are in range and inside the
// kernel support. Lanes past a range end read the array's padding and are masked off. Along
// periodic axes d is the minimum image.
#include <algorithm>
#include <type_traits>

#include "core/grid.h"
#include "core/kernels.h"
#include "core/simd.h"

namespace rtsph {

/// A kernel that also carries, in its type, whether the grids have periodic axes. Pair walks take
/// it as a template flag, so each sum is compiled once for the plain stencil (the fast path, as
/// without periodic axes) and once for the wrapped one, and the choice is made once per sum.
template <class K, bool P>
struct WithPeriodic : K {
  static constexpr bool periodic = P;
  explicit WithPeriodic(const K& k) : K(k) {}
};
template <class K>
inline constexpr bool periodic_v = std::decay_t<K>::periodic;

/// with_kernel (kernels.h) plus the periodic flag: fn gets a WithPeriodic<kernel, periodic>.
template <int D, class Fn>
decltype(auto) with_kernel(KernelType type, double h, bool periodic, Fn&& fn) {
  return with_kernel<D>(type, h, [&](const auto& k) -> decltype(auto) {
    using Kt = std::decay_t<decltype(k)>;
    if (periodic) return fn(WithPeriodic<Kt, true>(k));
    return fn(WithPeriodic<Kt, false>(k));
  });
}

namespace detail {
// One contiguous range [begin, end) of candidates, eight at a time: fn(j, d, r2, mask, valid),
// `valid` the lanes inside the range (the lanes past it read the next cells or the padding).
template <int D, bool kPeriodic, bool kSkipEmpty, class Fn>
[[gnu::always_inline]] inline void range_batches(const UniformGrid<D>& grid, const Real* const xs[D],
                                                 const Real xi[D], Real support2, uint32_t begin,
                                                 uint32_t end, Fn&& fn) {
  using simd::f8;
  using simd::i8;
  for (uint32_t j = begin; j < end; j += simd::kWidth) {
    f8 d[D];
    for (int k = 0; k < D; ++k) d[k] = xi[k] - simd::load(xs[k] + j);
    if constexpr (kPeriodic) grid.wrap_offsets(d);  // minimum image across a seam
    f8 r2 = f8{};
    for (int k = 0; k < D; ++k) r2 += d[k] * d[k];
    const int valid = int(std::min<uint32_t>(end - j, simd::kWidth));
    const i8 mask = (simd::lane_index() < valid) & (r2 < support2);
    if (!kSkipEmpty || simd::any(mask)) fn(j, d, r2, mask, valid);
  }
}
}  // namespace detail

// Forced inlining keeps the caller's accumulators in registers across batches. kSkipEmpty
// skips batches with no lane in range (worth its mispredicted branch when fn is heavy).
template <int D, bool kPeriodic, bool kSkipEmpty = true, class Fn>
[[gnu::always_inline]] inline void for_each_candidate_batch(const UniformGrid<D>& grid, uint32_t cell,
                                     const Real* const xs[D], const Real xi[D], Real support2,
                                     Fn&& fn) {
  if (grid.stencil_empty(cell)) return;  // nothing within a cell (mark_occupied_stencils)
  auto batches = [&](uint32_t begin, uint32_t end) {
    detail::range_batches<D, kPeriodic, kSkipEmpty>(grid, xs, xi, support2, begin, end,
        [&](uint32_t j, const simd::f8* d, simd::f8 r2, simd::i8 mask, int) { fn(j, d, r2, mask); });
  };
  if constexpr (kPeriodic)
    grid.for_each_periodic_range(cell, batches);
  else
    grid.for_each_flat_range(cell, batches);
}

/// The half-stencil walk (UniformGrid::for_each_forward_range, no periodic axes): particle i's
/// partners of higher sorted index, eight at a time, as fn(j, d, r2, mask, valid) with `valid`
/// the lanes inside the range (add_forward writes only those: the lanes past it belong to
/// other cells, which another thread may be writing).
template <int D, class Fn>
[[gnu::always_inline]] inline void for_each_forward_batch(const UniformGrid<D>& grid, uint32_t cell,
                                                          uint32_t i, const Real* const xs[D],
                                                          const Real xi[D], Real support2, Fn&& fn) {
  grid.for_each_forward_range(cell, i + 1, [&](uint32_t begin, uint32_t end) {
    detail::range_batches<D, false, true>(grid, xs, xi, support2, begin, end, fn);
  });
}

/// acc[j + l] += v[l] for the first `valid` lanes (the forward walk's write to its partners).
[[gnu::always_inline]] inline void add_forward(Real* acc, uint32_t j, simd::f8 v, int valid) {
  if (valid == simd::kWidth) {
    simd::store(acc + j, simd::load(acc + j) + v);
  } else {
    for (int l = 0; l < valid; ++l) acc[j + uint32_t(l)] += v[l];
  }
}

}  // namespace rtsph
