#include "core/parallel.h"

#include <omp.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>

namespace rtsph {

namespace detail {

// How long a worker spins for the next loop, and the caller for the workers' last blocks,
// before sleeping on a futex. A step is a chain of loops with microseconds of serial work
// between them, so a short spin catches the next one without a wake-up (about 65 µs on this
// guest); between steps of a viewer frame or when another process wants the core, the thread
// sleeps after at most this long (on a condition variable). Measured in docs/performance.md
// ("Threads").
constexpr std::chrono::microseconds kSpin{100};

namespace {
inline void cpu_relax() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#endif
}

// Spins until done() or kSpin has passed; returns done().
template <class Done>
bool spin_until(Done&& done) {
  const auto t0 = std::chrono::steady_clock::now();
  for (;;) {
    for (int k = 0; k < 64; ++k) {
      if (done()) return true;
      cpu_relax();
    }
    if (std::chrono::steady_clock::now() - t0 > kSpin) return done();
  }
}
}  // namespace

class Workers {
 public:
  explicit Workers(int count) {
    threads_.reserve(std::size_t(count));
    for (int w = 0; w < count; ++w) threads_.emplace_back([this, w] { loop(w); });
  }
  ~Workers() {
    stop_.store(true, std::memory_order_relaxed);
    job_.fetch_add(kGeneration, std::memory_order_release);
    wake(job_cv_);
    for (auto& t : threads_) t.join();
  }

  void run(int threads, std::size_t blocks, void* ctx, void (*call)(void*, std::size_t)) {
    // A loop started from inside a loop, or from a second thread while one runs, runs on its
    // caller alone: the blocks and their results are the same.
    if (busy_.exchange(true, std::memory_order_acquire)) return serial(blocks, ctx, call);
    const int helpers = std::min(threads - 1, int(threads_.size()));
    ctx_ = ctx;
    call_ = call;
    blocks_ = blocks;
    next_.store(0, std::memory_order_relaxed);
    gate_.store(0, std::memory_order_release);  // open, nobody in: publishes the fields above
    // A new generation with its helper count in one word, so a worker that is not asked reads
    // nothing else.
    const uint64_t next_generation = (job_.load(std::memory_order_relaxed) | (kGeneration - 1)) + 1;
    job_.store(next_generation | uint64_t(helpers), std::memory_order_release);
    wake(job_cv_);
    take_blocks();
    // Close the gate, then wait only for the workers that got in: one still asleep (or parked by
    // the scheduler) when the blocks ran out is not waited for, it finds the gate closed.
    if ((gate_.fetch_or(kClosed, std::memory_order_acq_rel) & ~kClosed) != 0) {
      auto all_out = [&] { return (gate_.load(std::memory_order_acquire) & ~kClosed) == 0; };
      if (!spin_until(all_out)) {
        std::unique_lock<std::mutex> lock(mutex_);
        done_cv_.wait(lock, all_out);
      }
    }
    busy_.store(false, std::memory_order_release);
  }

 private:
  // Taking the mutex between the store and the notify: a thread that checked its condition
  // under the mutex before the store is then already waiting, so it cannot miss the notify.
  void wake(std::condition_variable& cv) {
    { std::lock_guard<std::mutex> lock(mutex_); }
    cv.notify_all();
  }
  static void serial(std::size_t blocks, void* ctx, void (*call)(void*, std::size_t)) {
    for (std::size_t b = 0; b < blocks; ++b) call(ctx, b);
  }
  void take_blocks() {
    for (std::size_t b; (b = next_.fetch_add(1, std::memory_order_relaxed)) < blocks_;) call_(ctx_, b);
  }
  void loop(int w) {
    // A worker runs pool loops only: their floating-point mode for good (detail::FlushDenormals).
    const FlushDenormals flush;
    // The word before any loop, not a load: the first loop may be published before this thread
    // runs, and it must still take part.
    uint64_t seen = 0;
    for (;;) {
      auto new_job = [&] { return job_.load(std::memory_order_acquire) != seen; };
      if (!spin_until(new_job)) {
        std::unique_lock<std::mutex> lock(mutex_);
        job_cv_.wait(lock, new_job);
      }
      seen = job_.load(std::memory_order_acquire);
      if (stop_.load(std::memory_order_relaxed)) return;
      if (uint64_t(w) >= (seen & (kGeneration - 1))) continue;  // this loop asked for fewer threads
      if (!enter()) continue;  // the caller already ran every block
      take_blocks();
      if (gate_.fetch_sub(1, std::memory_order_acq_rel) == (kClosed | 1)) wake(done_cv_);
    }
  }
  // Joins the open loop (whichever it is: the fields are read only after this acquire).
  bool enter() {
    uint32_t g = gate_.load(std::memory_order_relaxed);
    while (!(g & kClosed))
      if (gate_.compare_exchange_weak(g, g + 1, std::memory_order_acquire, std::memory_order_relaxed)) return true;
    return false;
  }

  static constexpr uint64_t kGeneration = uint64_t(1) << 32;  // the low bits count helpers

  std::vector<std::thread> threads_;
  std::atomic<uint64_t> job_{0};          // generation (high bits) and helper count (low bits)
  static constexpr uint32_t kClosed = 0x80000000u;
  std::atomic<uint32_t> gate_{kClosed};   // kClosed once the caller is done, + workers inside
  std::atomic<std::size_t> next_{0};     // the next block to hand out
  std::atomic<bool> busy_{false};
  std::mutex mutex_;  // only for sleeping
  std::condition_variable job_cv_, done_cv_;
  // The current loop: written by the caller before the generation bump, read after it.
  void* ctx_ = nullptr;
  void (*call_)(void*, std::size_t) = nullptr;
  std::size_t blocks_ = 0;
  std::atomic<bool> stop_{false};
};

void run_blocks(Workers* workers, int threads, std::size_t blocks, void* ctx,
                void (*call)(void*, std::size_t)) {
  if (!workers || threads <= 1 || blocks <= 1) {
    for (std::size_t b = 0; b < blocks; ++b) call(ctx, b);
    return;
  }
  workers->run(threads, blocks, ctx, call);
}

}  // namespace detail

// omp_get_max_threads: the default follows OMP_NUM_THREADS, as users of OpenMP codes expect.
ThreadPool::ThreadPool(int threads) : threads_(threads > 0 ? threads : omp_get_max_threads()) {
  if (threads_ > 1) workers_ = std::make_unique<detail::Workers>(threads_ - 1);
}

ThreadPool::~ThreadPool() = default;

}  // namespace rtsph
