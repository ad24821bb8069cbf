#include "core/parallel.h"

#include <omp.h>

namespace rtsph {

ThreadPool::ThreadPool(int threads) : threads_(threads > 0 ? threads : omp_get_max_threads()) {}

namespace detail {
void run_blocks(int threads, std::size_t blocks, void* ctx, void (*call)(void*, std::size_t)) {
  if (threads <= 1 || blocks <= 1) {
    for (std::size_t b = 0; b < blocks; ++b) call(ctx, b);
    return;
  }
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
  for (std::size_t b = 0; b < blocks; ++b) call(ctx, b);
}
}  // namespace detail

}  // namespace rtsph
