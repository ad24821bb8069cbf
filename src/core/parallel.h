#pragma once
// The one place that knows about threads. Work is split into contiguous index ranges with a
// static schedule, and every per-particle result depends only on that particle's own inputs,
// so results are bitwise identical for any thread count.
#include <algorithm>
#include <cstddef>
#include <type_traits>
#include <vector>

namespace rtsph {

class ThreadPool {
 public:
  explicit ThreadPool(int threads);  // 0 = all hardware threads
  int threads() const { return threads_; }

  /// Calls fn(begin, end) on disjoint ranges covering [0, n).
  template <class Fn>
  void parallel_for(std::size_t n, Fn&& fn) const;

  /// Deterministic sum: a fixed number of blocks, independent of the thread count, reduced in
  /// block order. fn(begin, end) returns the block's partial value.
  template <class T, class Fn>
  T parallel_reduce(std::size_t n, T zero, Fn&& fn) const;

 private:
  int threads_;
};

/// Reduction value that combines by maximum, for parallel_reduce.
template <class T>
struct MaxOf {
  T value;
  MaxOf& operator+=(const MaxOf& o) { if (o.value > value) value = o.value; return *this; }
};

namespace detail {
void run_blocks(int threads, std::size_t blocks, void* ctx, void (*call)(void*, std::size_t));
}

template <class Fn>
void ThreadPool::parallel_for(std::size_t n, Fn&& fn) const {
  if (n == 0) return;
  // A few blocks per thread balances uneven neighbour counts; the split never changes results.
  const std::size_t blocks = std::min<std::size_t>(n, static_cast<std::size_t>(threads_) * 8);
  struct Ctx { std::remove_reference_t<Fn>* fn; std::size_t n, blocks; } ctx{&fn, n, blocks};
  detail::run_blocks(threads_, blocks, &ctx, [](void* p, std::size_t b) {
    auto& c = *static_cast<Ctx*>(p);
    const std::size_t lo = c.n * b / c.blocks, hi = c.n * (b + 1) / c.blocks;
    if (lo < hi) (*c.fn)(lo, hi);
  });
}

template <class T, class Fn>
T ThreadPool::parallel_reduce(std::size_t n, T zero, Fn&& fn) const {
  constexpr std::size_t kBlocks = 64;
  T partial[kBlocks];
  for (auto& p : partial) p = zero;
  const std::size_t blocks = std::min<std::size_t>(kBlocks, n);
  if (blocks == 0) return zero;
  struct Ctx { std::remove_reference_t<Fn>* fn; T* out; std::size_t n, blocks; } ctx{&fn, partial, n, blocks};
  detail::run_blocks(threads_, blocks, &ctx, [](void* p, std::size_t b) {
    auto& c = *static_cast<Ctx*>(p);
    c.out[b] = (*c.fn)(c.n * b / c.blocks, c.n * (b + 1) / c.blocks);
  });
  T total = zero;
  for (std::size_t b = 0; b < blocks; ++b) total += partial[b];
  return total;
}

}  // namespace rtsph
