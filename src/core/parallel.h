#pragma once
// The one place that knows about threads. Work is split into contiguous index ranges with a
// static schedule, and every per-particle result depends only on that particle's own inputs,
// so results are bitwise identical for any thread count.
#include <algorithm>
#include <cstddef>
#include <memory>
#include <type_traits>
#include <vector>

#if defined(__SSE__)
#include <xmmintrin.h>
#endif

namespace rtsph {

namespace detail {
class Workers;

/// Flush-to-zero and denormals-are-zero for the scope (x86's MXCSR; nothing elsewhere), the
/// caller's mode restored after. Every pool loop runs under it, on the caller and on the workers,
/// so a result never depends on the thread or the entry point (CLI, Python, tests) that ran it.
/// Values below 1.2e-38 are noise in every sum here (kernel tails, s_corr's fourth powers), and
/// on Intel each operation that makes or reads one takes a microcode assist: about 3% of a PBF
/// and of a WCSPH step (medians of five alternating runs, docs/performance.md, "Session 23").
class FlushDenormals {
 public:
#if defined(__SSE__)
  FlushDenormals() : saved_(_mm_getcsr()) { _mm_setcsr(saved_ | kFlags); }
  ~FlushDenormals() { _mm_setcsr(saved_); }
  static constexpr unsigned kFlags = 0x8040;  // FTZ (bit 15) | DAZ (bit 6)

 private:
  unsigned saved_;
#endif
};
}  // namespace detail

/// Owns threads-1 worker threads (the caller is the last one), started with the pool and joined
/// when it is destroyed, so two simulations never share workers.
class ThreadPool {
 public:
  explicit ThreadPool(int threads);  // 0 = all hardware threads
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;
  int threads() const { return threads_; }

  // Waking a sleeping worker costs about 65 µs here (futex wake under a hypervisor: a 2D
  // WCSPH step of ~10 regions at 990 particles took 0.75 ms on 2 threads against 0.1 ms on 1).
  // Workers therefore spin briefly after each loop before they sleep (detail::kSpin), which
  // catches the next loop of the same step, and a loop only gets as many threads as it has
  // `grain` elements per thread. Element-wise loops (a few ns per element) keep the default;
  // pair sums (0.3–1 µs per particle) pass kPairs. The thread count never changes results, so
  // neither does the grain. With the spinning workers, 8,192 elements per thread pays: from
  // 32,768, WCSPH at 60k ran 7% faster (its EOS, permutations and reductions had run on one
  // thread), and nothing below 16k particles changed. 4,096 gained a few percent between 8k
  // and 16k, with outliers where a loop's work is about what a hand-off costs (a 10k kick)
  // (docs/performance.md, "Session 25").
  static constexpr std::size_t kCheap = 8192;
  static constexpr std::size_t kPairs = 512;

  /// Calls fn(begin, end) on disjoint ranges covering [0, n).
  template <class Fn>
  void parallel_for(std::size_t n, Fn&& fn, std::size_t grain = kCheap) const;

  /// Deterministic sum: a fixed number of blocks, independent of the thread count, reduced in
  /// block order. fn(begin, end) returns the block's partial value.
  template <class T, class Fn>
  T parallel_reduce(std::size_t n, T zero, Fn&& fn, std::size_t grain = kCheap) const;

 private:
  int threads_for(std::size_t n, std::size_t grain) const {
    return int(std::min<std::size_t>(std::size_t(threads_), std::max<std::size_t>(1, n / std::max<std::size_t>(grain, 1))));
  }
  int threads_;
  std::unique_ptr<detail::Workers> workers_;  // null with one thread
};

/// Reduction value that combines by maximum, for parallel_reduce.
template <class T>
struct MaxOf {
  T value;
  MaxOf& operator+=(const MaxOf& o) { if (o.value > value) value = o.value; return *this; }
};

namespace detail {
/// Runs call(ctx, b) for every b in [0, blocks) on up to `threads` threads (the caller and
/// threads-1 of `workers`), each block exactly once; returns when all are done. Blocks are
/// handed out dynamically, which never changes results: what a block computes is fixed.
void run_blocks(Workers* workers, int threads, std::size_t blocks, void* ctx,
                void (*call)(void*, std::size_t));
}

template <class Fn>
void ThreadPool::parallel_for(std::size_t n, Fn&& fn, std::size_t grain) const {
  if (n == 0) return;
  const detail::FlushDenormals flush;
  const int threads = threads_for(n, grain);
  if (threads <= 1) return fn(std::size_t(0), n);
  // A few blocks per thread balances uneven neighbour counts; the split never changes results.
  const std::size_t blocks = std::min<std::size_t>(n, static_cast<std::size_t>(threads) * 8);
  struct Ctx { std::remove_reference_t<Fn>* fn; std::size_t n, blocks; } ctx{&fn, n, blocks};
  detail::run_blocks(workers_.get(), threads, blocks, &ctx, [](void* p, std::size_t b) {
    auto& c = *static_cast<Ctx*>(p);
    const std::size_t lo = c.n * b / c.blocks, hi = c.n * (b + 1) / c.blocks;
    if (lo < hi) (*c.fn)(lo, hi);
  });
}

template <class T, class Fn>
T ThreadPool::parallel_reduce(std::size_t n, T zero, Fn&& fn, std::size_t grain) const {
  constexpr std::size_t kBlocks = 64;
  T partial[kBlocks];
  for (auto& p : partial) p = zero;
  const std::size_t blocks = std::min<std::size_t>(kBlocks, n);
  if (blocks == 0) return zero;
  const detail::FlushDenormals flush;
  struct Ctx { std::remove_reference_t<Fn>* fn; T* out; std::size_t n, blocks; } ctx{&fn, partial, n, blocks};
  detail::run_blocks(workers_.get(), threads_for(n, grain), blocks, &ctx, [](void* p, std::size_t b) {
    auto& c = *static_cast<Ctx*>(p);
    c.out[b] = (*c.fn)(c.n * b / c.blocks, c.n * (b + 1) / c.blocks);
  });
  T total = zero;
  for (std::size_t b = 0; b < blocks; ++b) total += partial[b];
  return total;
}

}  // namespace rtsph
