// ThreadPool (src/core/parallel.h): parallel_for covers [0, n) exactly once with disjoint,
// non-empty ranges; parallel_reduce is bitwise independent of the thread count; MaxOf.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "core/parallel.h"

namespace rtsph {
namespace {

TEST(ThreadPool, ThreadCount) {
  EXPECT_EQ(ThreadPool(1).threads(), 1);
  EXPECT_EQ(ThreadPool(3).threads(), 3);
  EXPECT_GE(ThreadPool(0).threads(), 1);  // 0 = all hardware threads
}

TEST(ParallelFor, CoversEveryIndexExactlyOnce) {
  for (int threads : {1, 2, 3}) {
    const ThreadPool pool(threads);
    for (std::size_t n : {0u, 1u, 7u, 1000u, 100003u}) {
      std::unique_ptr<std::atomic<int>[]> hits(new std::atomic<int>[n + 1]);
      for (std::size_t i = 0; i <= n; ++i) hits[i] = 0;
      std::atomic<int> calls{0}, bad{0};
      std::mutex mu;
      std::vector<std::pair<std::size_t, std::size_t>> ranges;
      pool.parallel_for(n, [&](std::size_t b, std::size_t e) {
        ++calls;
        if (!(b < e && e <= n)) ++bad;  // ranges are non-empty and inside [0, n)
        for (std::size_t i = b; i < e && i <= n; ++i) hits[i].fetch_add(1);
        std::lock_guard<std::mutex> lock(mu);
        ranges.emplace_back(b, e);
      });
      EXPECT_EQ(bad.load(), 0) << "threads=" << threads << " n=" << n;
      for (std::size_t i = 0; i < n; ++i)
        ASSERT_EQ(hits[i].load(), 1) << "index " << i << " threads=" << threads << " n=" << n;
      EXPECT_EQ(hits[n].load(), 0) << "index n touched, threads=" << threads;
      if (n == 0) {
        EXPECT_EQ(calls.load(), 0) << "parallel_for(0) must not call fn";
      }
      std::size_t covered = 0;
      for (auto [b, e] : ranges) covered += e - b;
      EXPECT_EQ(covered, n) << "threads=" << threads;
    }
  }
}

TEST(ParallelFor, LargeRangeWithTwoThreadsSumsCorrectly) {
  // 16 blocks over 65536 indices on 2 threads: the block sums add up to the closed form.
  const ThreadPool pool(2);
  std::atomic<std::size_t> sum{0};
  pool.parallel_for(1 << 16, [&](std::size_t b, std::size_t e) {
    std::size_t s = 0;
    for (std::size_t i = b; i < e; ++i) s += i;
    sum += s;
  });
  EXPECT_EQ(sum.load(), (std::size_t(1) << 16) * ((std::size_t(1) << 16) - 1) / 2);
}

// Workers spin between loops and sleep after a while: thousands of back-to-back loops of
// changing width (a loop asking for fewer threads than the pool has), with pauses long enough
// for the workers to fall asleep, must each run every block once and return.
TEST(ParallelFor, ManyLoopsInARowWithChangingWidths) {
  const ThreadPool pool(3);
  for (int round = 0; round < 3000; ++round) {
    const std::size_t n = std::size_t(1 + round % 5) * 600;  // 1 to 3 threads at grain 512
    std::atomic<std::size_t> sum{0};
    pool.parallel_for(n, [&](std::size_t b, std::size_t e) {
      std::size_t s = 0;
      for (std::size_t i = b; i < e; ++i) s += i;
      sum += s;
    }, 512);
    ASSERT_EQ(sum.load(), n * (n - 1) / 2) << "round " << round;
    if (round % 1000 == 999) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

// A loop started inside a loop's body runs on the calling thread and still covers its range.
TEST(ParallelFor, NestedLoopRunsOnItsCaller) {
  const ThreadPool pool(2);
  std::atomic<std::size_t> inner{0};
  pool.parallel_for(4096, [&](std::size_t b, std::size_t e) {
    pool.parallel_for(e - b, [&](std::size_t ib, std::size_t ie) { inner += ie - ib; }, 1);
  }, 512);
  EXPECT_EQ(inner.load(), 4096u);
}

double term(std::size_t i) { return std::sin(double(i) * 0.37) / double(i + 1) + 1e-3 * double(i % 7); }

double block_sum(std::size_t b, std::size_t e) {
  double s = 0;
  for (std::size_t i = b; i < e; ++i) s += term(i);
  return s;
}

// Passed as a prvalue lambda: parallel_for/parallel_reduce store `Fn*` with Fn deduced from a
// forwarding reference, so an lvalue callable (a named lambda or a function name) does not
// compile ("forming pointer to reference type", src/core/parallel.h:45 and :60).
const auto kBlockSum = [](std::size_t b, std::size_t e) { return block_sum(b, e); };
using BlockSum = decltype(kBlockSum);

uint64_t bits(double d) {
  uint64_t u;
  std::memcpy(&u, &d, sizeof u);
  return u;
}

#if defined(__SSE__)
// Pool loops flush denormals (detail::FlushDenormals), on the caller and on the workers, for
// parallel_for and parallel_reduce alike, and leave the caller's mode as it was.
TEST(ParallelFor, DenormalsAreZeroInsideLoopsAndTheModeIsRestored) {
  volatile float tiny = 1e-40f;  // below FLT_MIN: a denormal
  ASSERT_GT(tiny * 3.0f, 0.0f);  // outside any loop: kept
  for (int threads : {1, 2}) {
    ThreadPool pool(threads);
    std::vector<float> out(4096, -1.0f);
    pool.parallel_for(out.size(), [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i) out[i] = tiny * 3.0f;
    }, 1);
    for (float v : out) ASSERT_EQ(v, 0.0f) << threads << " threads";
    const double sum = pool.parallel_reduce(out.size(), 0.0, [&](std::size_t b, std::size_t e) {
      double s = 0;
      for (std::size_t i = b; i < e; ++i) s += double(tiny * 3.0f);
      return s;
    }, 1);
    EXPECT_EQ(sum, 0.0) << threads << " threads";
    EXPECT_GT(tiny * 3.0f, 0.0f) << "the caller's mode after the loops";
  }
}
#endif

TEST(ParallelReduce, BitwiseIdenticalForThreadCounts) {
  for (std::size_t n : {0u, 1u, 7u, 63u, 64u, 65u, 1000u, 123457u}) {
    const double s1 = ThreadPool(1).parallel_reduce(n, 0.0, BlockSum(kBlockSum));
    const double s2 = ThreadPool(2).parallel_reduce(n, 0.0, BlockSum(kBlockSum));
    const double s3 = ThreadPool(3).parallel_reduce(n, 0.0, BlockSum(kBlockSum));
    EXPECT_EQ(bits(s1), bits(s2)) << "n=" << n << ": " << s1 << " vs " << s2;
    EXPECT_EQ(bits(s1), bits(s3)) << "n=" << n << ": " << s1 << " vs " << s3;
    // And it is the sum: compare with a compensated serial sum.
    long double ref = 0;
    for (std::size_t i = 0; i < n; ++i) ref += term(i);
    EXPECT_NEAR(s1, double(ref), 1e-12 * (1 + std::abs(double(ref)))) << "n=" << n;
    // Repeating gives the same bits too (no dependence on scheduling).
    for (int rep = 0; rep < 5; ++rep)
      EXPECT_EQ(bits(ThreadPool(3).parallel_reduce(n, 0.0, BlockSum(kBlockSum))), bits(s1)) << "n=" << n;
  }
}

TEST(ParallelReduce, BlocksCoverRangeExactlyOnce) {
  for (int threads : {1, 2, 3}) {
    for (std::size_t n : {0u, 1u, 7u, 1000u}) {
      std::vector<std::atomic<int>> hits(n + 1);
      const std::size_t count = ThreadPool(threads).parallel_reduce(
          n, std::size_t(0), [&](std::size_t b, std::size_t e) {
            for (std::size_t i = b; i < e; ++i) hits[i].fetch_add(1);
            return e - b;
          });
      EXPECT_EQ(count, n) << "threads=" << threads;
      for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(hits[i].load(), 1) << "i=" << i;
    }
  }
}

TEST(ParallelReduce, EmptyReturnsZeroValue) {
  EXPECT_EQ(ThreadPool(2).parallel_reduce(0, 42.5, BlockSum(kBlockSum)), 42.5);
}

TEST(MaxOf, CombinesByMaximum) {
  MaxOf<double> m{-1.0};
  m += MaxOf<double>{-5.0};
  EXPECT_EQ(m.value, -1.0);
  m += MaxOf<double>{3.0};
  EXPECT_EQ(m.value, 3.0);
  m += MaxOf<double>{3.0};
  EXPECT_EQ(m.value, 3.0);
}

TEST(MaxOf, ParallelReduceFindsMaximum) {
  std::vector<double> v(54321);
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = std::sin(double(i) * 1.7) * double(i % 101);
  v[40000] = 1234.5;  // the unique maximum, far from the first block
  for (int threads : {1, 2, 3}) {
    for (std::size_t n : {1u, 7u, 1000u, 54321u}) {
      const auto r = ThreadPool(threads).parallel_reduce(
          n, MaxOf<double>{-std::numeric_limits<double>::infinity()},
          [&](std::size_t b, std::size_t e) {
            MaxOf<double> m{-std::numeric_limits<double>::infinity()};
            for (std::size_t i = b; i < e; ++i) m += MaxOf<double>{v[i]};
            return m;
          });
      double expect = -std::numeric_limits<double>::infinity();
      for (std::size_t i = 0; i < n; ++i) expect = std::max(expect, v[i]);
      EXPECT_EQ(r.value, expect) << "threads=" << threads << " n=" << n;
    }
  }
  // All-negative input: the zero value (-inf) must not win.
  const auto r = ThreadPool(2).parallel_reduce(100, MaxOf<float>{-std::numeric_limits<float>::infinity()},
                                               [](std::size_t b, std::size_t) {
                                                 return MaxOf<float>{-1.0f - float(b)};
                                               });
  EXPECT_EQ(r.value, -1.0f);
}

}  // namespace
}  // namespace rtsph
