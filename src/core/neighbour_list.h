#pragma once
// Per-particle lists of the fluid neighbours found by one grid walk, for methods that sum over
// the same neighbourhood many times per step (PBF's constraint iterations, DFSPH's pressure
// sweeps). A grid walk visits ~200 candidates per particle in 3D of which ~30 are in range; a
// list visits only those, eight at a time through gathers. Each list holds the particle itself
// and its neighbours in grid-walk order, padded to a multiple of eight with i itself (the
// padding lanes are masked off by count, and i is always a valid address to gather from).
// The content depends only on the positions and the sort, never on the thread count.
#include <cstdint>
#include <cstring>

#include "core/aligned_array.h"
#include "core/grid.h"
#include "core/simd.h"

namespace rtsph {

template <int D>
class NeighbourList {
 public:
  /// Lists, for each of the n particles the grid was built over, every j with |xᵢ − xⱼ|² < r2.
  void build(const UniformGrid<D>& grid, const Real* const xs[D], std::size_t n, Real r2,
             const ThreadPool& pool);
  void clear() { n_ = 0; valid_ = false; }
  /// False until built, and after clear(): callers fall back to the grid walk.
  bool valid() const { return valid_; }
  std::size_t size() const { return n_; }
  const uint32_t* begin(std::size_t i) const { return idx_.data() + i * stride_; }
  /// Slots per particle (a multiple of 8): per-pair caches index slot i·stride() + s.
  std::size_t stride() const { return stride_; }
  uint32_t count(std::size_t i) const { return count_[i]; }
  double mean_count() const;
  std::size_t bytes() const { return idx_.bytes() + count_.bytes(); }
  /// The grid the list was built from: its periodic axes give the walk its minimum image.
  const UniformGrid<D>* grid() const { return grid_; }

 private:
  AlignedArray<uint32_t> idx_, count_;
  const UniformGrid<D>* grid_ = nullptr;
  std::size_t n_ = 0, stride_ = 0;
  bool valid_ = false;
};

/// Walks particle i's list eight at a time: fn(j, d, r2, mask) as for_each_candidate_batch,
/// with j the lanes' particle indices (an i8: read fields with simd::at(array, j)). Positions
/// are re-read, so the sums see particles that moved since the list was built.
template <int D, class Fn>
[[gnu::always_inline]] inline void for_each_listed_batch(const NeighbourList<D>& list,
                                                         std::size_t i, const Real* const xs[D],
                                                         const Real xi[D], Real support2,
                                                         Fn&& fn) {
  using simd::f8;
  using simd::i8;
  const uint32_t* idx = list.begin(i);
  const int count = int(list.count(i));
  const bool periodic = list.grid()->any_periodic();
  for (int s = 0; s < count; s += simd::kWidth) {
    i8 j;
    std::memcpy(&j, idx + s, sizeof j);
    f8 d[D];
    for (int k = 0; k < D; ++k) d[k] = xi[k] - simd::at(xs[k], j);
    if (periodic) list.grid()->wrap_offsets(d);  // minimum image across a seam
    f8 r2 = f8{};
    for (int k = 0; k < D; ++k) r2 += d[k] * d[k];
    const i8 mask = (simd::lane_index() < count - s) & (r2 < support2);
    fn(j, d, r2, mask);
  }
}

/// Walks particle i's list eight at a time for per-pair caches written by an earlier walk at
/// the same positions: fn(j, slot) with j the lanes' particle indices and slot the cache index
/// of the first lane (i·stride() + s). Positions are not read; masked lanes hold whatever the
/// writer stored for them (zeros, by convention), so no mask is passed.
template <int D, class Fn>
[[gnu::always_inline]] inline void for_each_cached_batch(const NeighbourList<D>& list,
                                                         std::size_t i, Fn&& fn) {
  const uint32_t* idx = list.begin(i);
  const int count = int(list.count(i));
  const std::size_t base = i * list.stride();
  for (int s = 0; s < count; s += simd::kWidth) {
    simd::i8 j;
    std::memcpy(&j, idx + s, sizeof j);
    fn(j, base + std::size_t(s));
  }
}

}  // namespace rtsph
