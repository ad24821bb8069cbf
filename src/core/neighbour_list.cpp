#include "core/neighbour_list.h"

#include <type_traits>

#include <algorithm>
#include <atomic>
#include <cstring>

#include "core/pair_loop.h"

namespace rtsph {

namespace {

// The list build's candidate walk: emit(j, bits) for each batch of kListWidth candidates from j,
// bits the lanes within r2 (lanes past the range end clear). Sixteen lanes where the CPU has
// AVX-512, eight otherwise. The build tests every candidate and keeps ~15%, with no per-pair
// work beyond the test, so the test is what a wider batch speeds up; the pair sums, whose
// ranges and lists fill a sixteen-lane batch worse, stay at eight (docs/performance.md,
// session 24). Candidates come in the same order either way, so the lists are the same.
#if defined(__AVX512F__)
constexpr uint32_t kListWidth = 16;
#else
constexpr uint32_t kListWidth = simd::kWidth;
#endif

template <int D, bool kPeriodic, class Emit>
[[gnu::always_inline]] inline void list_batches(const UniformGrid<D>& grid, uint32_t cell,
                                                const Real* const xs[D], const Real xi[D], Real r2max,
                                                Emit&& emit) {
#if defined(__AVX512F__)
  typedef float v16 __attribute__((vector_size(64)));
  auto ranges = [&](uint32_t begin, uint32_t end) {
    for (uint32_t j = begin; j < end; j += kListWidth) {
      v16 d[D];
      for (int k = 0; k < D; ++k) d[k] = xi[k] - v16(_mm512_loadu_ps(xs[k] + j));
      if constexpr (kPeriodic) grid.wrap_offsets(d);  // minimum image across a seam
      v16 r2 = v16{};
      for (int k = 0; k < D; ++k) r2 += d[k] * d[k];
      const uint32_t valid = std::min(end - j, kListWidth);
      const __mmask16 in = _mm512_cmp_ps_mask(__m512(r2), _mm512_set1_ps(r2max), _CMP_LT_OQ);
      emit(j, unsigned(in) & ((1u << valid) - 1u));
    }
  };
  if constexpr (kPeriodic)
    grid.for_each_periodic_range(cell, ranges);
  else
    grid.for_each_flat_range(cell, ranges);
#else
  for_each_candidate_batch<D, kPeriodic, false>(grid, cell, xs, xi, r2max,
                                                [&](uint32_t j, const simd::f8*, simd::f8, simd::i8 m) {
                                                  emit(j, simd::bits(m));
                                                });
#endif
}

// Writes j + l for each lane l set in bits, in lane order, to out (kListWidth slots of room).
[[gnu::always_inline]] inline void store_lanes(uint32_t* out, uint32_t j, unsigned bits) {
#if defined(__AVX512F__)
  const __m512i lanes = _mm512_set_epi32(15, 14, 13, 12, 11, 10, 9, 8, 7, 6, 5, 4, 3, 2, 1, 0);
  _mm512_mask_compressstoreu_epi32(out, __mmask16(bits), _mm512_add_epi32(lanes, _mm512_set1_epi32(int(j))));
#else
  simd::store_packed(out, j, bits);
#endif
}

}  // namespace

template <int D>
void NeighbourList<D>::build(const UniformGrid<D>& grid, const Real* const xs[D], std::size_t n,
                             Real r2, const ThreadPool& pool) {
  n_ = n;
  grid_ = &grid;
  count_.resize(n);
  const uint32_t* cells = grid.sorted_cells();
  // One pass into a fixed stride; a particle with more neighbours than the stride grows it to
  // the largest count seen and the pass repeats (rare: compressed fluid). The result does not
  // depend on the guess. Then the lists are packed back to back.
  if (stride_ == 0) stride_ = D == 3 ? 64 : 24;
  for (;;) {
    scratch_.resize(n * stride_);
    std::atomic<uint32_t> largest{0};
    const std::size_t stride = stride_;
    // The walk compiled for the grid's kind (plain or periodic), chosen once per build.
    auto pass = [&](auto periodic) {
    pool.parallel_for(n, [&](std::size_t b, std::size_t e) {
      uint32_t local_largest = 0;
      for (std::size_t i = b; i < e; ++i) {
        Real xi[D];
        for (int k = 0; k < D; ++k) xi[k] = xs[k][i];
        uint32_t* out = scratch_.data() + i * stride;
        uint32_t c = 0;
// Every batch, even one with no lane in range: ~30% are, unpredictably, and the
// left-pack below is branch-free (build 1.13 -> 0.75 ms at 13k particles in 3D).
        list_batches<D, decltype(periodic)::value>(grid, cells[i], xs, xi, r2,
                                    [&](uint32_t j, unsigned bits) {
                                      // Branch-free left-pack of the lanes in range: a bit loop
                                      // mispredicts on nearly every batch.
                                      if (c + kListWidth <= stride) {
                                        store_lanes(out + c, j, bits);
                                      } else {  // near the end: only in-bounds slots
                                        uint32_t k = c;
                                        for (unsigned r = bits; r; r &= r - 1, ++k)
                                          if (k < stride) out[k] = j + uint32_t(__builtin_ctz(r));
                                      }
                                      c += uint32_t(__builtin_popcount(bits));
                                    });
        count_[i] = c;
        local_largest = std::max(local_largest, c);
        // Padding lanes gather from i itself, an address that always exists.
        for (uint32_t p = c; p < std::min<std::size_t>(stride, (c + 7u) & ~7u); ++p) out[p] = uint32_t(i);
      }
      uint32_t seen = largest.load(std::memory_order_relaxed);
      while (local_largest > seen && !largest.compare_exchange_weak(seen, local_largest)) {}
    }, ThreadPool::kPairs);
    };
    if (grid.any_periodic())
      pass(std::true_type{});
    else
      pass(std::false_type{});
    const std::size_t need = (std::size_t(largest.load()) + 7u) & ~std::size_t(7);
    if (need <= stride_) break;
    stride_ = need;
  }
  first_.resize(n + 1);
  std::size_t slot = 0;
  for (std::size_t i = 0; i < n; ++i) {
    first_[i] = slot;
    slot += (count_[i] + 7u) & ~7u;
  }
  first_[n] = slot;
  slots_ = slot;
  idx_.resize(slots_);
  const std::size_t stride = stride_;
  pool.parallel_for(n, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i)
      std::memcpy(idx_.data() + first_[i], scratch_.data() + i * stride,
                  (first_[i + 1] - first_[i]) * sizeof(uint32_t));
  });
  valid_ = true;
}

template <int D>
double NeighbourList<D>::mean_count() const {
  double s = 0;
  for (std::size_t i = 0; i < n_; ++i) s += count_[i];
  return n_ ? s / double(n_) : 0.0;
}

template class NeighbourList<2>;
template class NeighbourList<3>;

}  // namespace rtsph
