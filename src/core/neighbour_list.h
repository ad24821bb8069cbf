#pragma once
// Per-particle lists of the fluid neighbours found by one grid walk, for methods that sum over
// the same neighbourhood many times per step (PBF's constraint iterations, DFSPH's pressure
// sweeps). A grid walk visits ~200 candidates per particle in 3D of which ~30 are in range; a
// list visits only those, eight at a time through gathers. Each list holds the particle itself
// and its neighbours in grid-walk order, padded to a multiple of eight with i itself (the
// padding lanes are masked off by count, and i is always a valid address to gather from).
// The lists lie back to back (particle i's from slot first_slot(i)), and the per-pair caches
// (PairCache) use the same packed slots. With a fixed stride of 64 slots per particle, DFSPH's
// 3D sweeps at 60k particles streamed ~60 MB with ~40% of each particle's share unused and cost
// ~95 cycles per batch of eight pairs (a bare gather-and-FMA loop: ~22); packed, with huge
// pages for the large arrays, `rtsph bench --method dfsph --dim 3 --particles 60000` went from
// 7.0e5 to 2.3e6 fluid particle-steps/s (10 steps from rest).
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
  const uint32_t* begin(std::size_t i) const { return idx_.data() + first_[i]; }
  /// Particle i's first slot (a multiple of 8); its lanes are slots first_slot(i) + s.
  std::size_t first_slot(std::size_t i) const { return first_[i]; }
  /// Slots of all lists (a multiple of 8): the size of a per-pair cache with one field.
  std::size_t slots() const { return slots_; }
  uint32_t count(std::size_t i) const { return count_[i]; }
  double mean_count() const;
  std::size_t bytes() const {
    return idx_.bytes() + count_.bytes() + first_.bytes() + scratch_.bytes();
  }
  /// The grid the list was built from: its periodic axes give the walk its minimum image.
  const UniformGrid<D>* grid() const { return grid_; }

 private:
  AlignedArray<uint32_t> idx_, count_;
  AlignedArray<std::size_t> first_;
  AlignedArray<uint32_t> scratch_;  // the walk's output at a fixed stride, before packing
  const UniformGrid<D>* grid_ = nullptr;
  std::size_t n_ = 0, stride_ = 0, slots_ = 0;
  bool valid_ = false;
};

namespace detail {
/// The list walk, with load(j, x) filling x[D] with the lanes' positions.
template <int D, class Load, class Fn>
[[gnu::always_inline]] inline void walk_listed(const NeighbourList<D>& list, std::size_t i,
                                               const Real xi[D], Real support2, Load&& load,
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
    load(j, d);
    for (int k = 0; k < D; ++k) d[k] = xi[k] - d[k];
    if (periodic) list.grid()->wrap_offsets(d);  // minimum image across a seam
    f8 r2 = f8{};
    for (int k = 0; k < D; ++k) r2 += d[k] * d[k];
    const i8 mask = (simd::lane_index() < count - s) & (r2 < support2);
    fn(j, d, r2, mask);
  }
}
}  // namespace detail

/// Walks particle i's list eight at a time: fn(j, d, r2, mask) as for_each_candidate_batch,
/// with j the lanes' particle indices (an i8: read fields with simd::at(array, j)). Positions
/// are re-read, so the sums see particles that moved since the list was built.
template <int D, class Fn>
[[gnu::always_inline]] inline void for_each_listed_batch(const NeighbourList<D>& list,
                                                         std::size_t i, const Real* const xs[D],
                                                         const Real xi[D], Real support2,
                                                         Fn&& fn) {
  detail::walk_listed<D>(list, i, xi, support2, [&](simd::i8 j, simd::f8* x) {
    for (int k = 0; k < D; ++k) x[k] = simd::at(xs[k], j);
  }, fn);
}

/// for_each_listed_batch with the positions read from records instead of one gather per axis:
/// 16-byte (x, y, z, ·) records in 3D (simd::at_packed3), 8-byte (x, y) ones in 2D
/// (simd::at_packed2).
template <int D, class Fn>
[[gnu::always_inline]] inline void for_each_listed_batch_packed(const NeighbourList<D>& list,
                                                                std::size_t i, const Real* rec,
                                                                const Real xi[D], Real support2,
                                                                Fn&& fn) {
  detail::walk_listed<D>(list, i, xi, support2, [&](simd::i8 j, simd::f8* x) {
    if constexpr (D == 3)
      simd::at_packed3(rec, j, x[0], x[1], x[2]);
    else
      simd::at_packed2(rec, j, x[0], x[1]);
  }, fn);
}

/// Walks particle i's list eight at a time for per-pair caches written by an earlier walk at
/// the same positions: fn(j, slot) with j the lanes' particle indices and slot the first lane's
/// slot (first_slot(i) + s). Positions are not read; masked lanes hold whatever the writer
/// stored for them (zeros, by convention), so no mask is passed.
template <int D, class Fn>
[[gnu::always_inline]] inline void for_each_cached_batch(const NeighbourList<D>& list,
                                                         std::size_t i, Fn&& fn) {
  const uint32_t* idx = list.begin(i);
  const int count = int(list.count(i));
  const std::size_t base = list.first_slot(i);
  for (int s = 0; s < count; s += simd::kWidth) {
    simd::i8 j;
    std::memcpy(&j, idx + s, sizeof j);
    fn(j, base + std::size_t(s));
  }
}

/// Per-pair values cached by one walk for the next ones, F fields per listed pair, each field a
/// packed array over the lists' slots (field k of slot s at data[k·slots + s]). Measured
/// against a batch's F fields kept together: DFSPH 3D at 60k 2.33e6 against 1.85e6 fluid
/// particle-steps/s; PBF alike within noise.
template <int F>
struct PairCache {
  AlignedArray<Real> data;
  std::size_t slots = 0;
  template <int D>
  void resize(const NeighbourList<D>& list) {
    slots = list.slots();
    data.resize(slots * F);
  }
  /// Field k from slot s on (s a multiple of 8 for aligned loads).
  Real* at(std::size_t slot, int k) { return data.data() + std::size_t(k) * slots + slot; }
  const Real* at(std::size_t slot, int k) const { return data.data() + std::size_t(k) * slots + slot; }
  std::size_t bytes() const { return data.bytes(); }
};

}  // namespace rtsph
