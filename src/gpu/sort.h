#pragma once
// Sorting particles into the neighbour grid's cells on the GPU (Green 2008; Hoetzlein 2014): a
// counting sort by cell key (counts, an exclusive scan that is also each cell's first particle,
// a scatter), with each cell then ordered by the particles' previous indices. No atomic decides
// the final order, so it, and every sum that follows it, is the same on every run, and equals
// the CPU's stable counting sort (core/grid.cpp) for the same keys.
#include <cstddef>
#include <string>
#include <vector>

#include "gpu/gl_compute.h"

namespace rtsph::gpu {

/// A sorted set of particles: keys[i] and order[i] (new i ← old order[i]) for the sorted
/// order, start[c] .. start[c+1] the particles of cell c.
struct SortedCells {
  Buffer keys, order, start;
};

class CellSorter {
 public:
  /// `defines` are the backend's DIM and KERNEL (every program sees the shared common.glsl).
  explicit CellSorter(const std::vector<std::string>& defines);

  /// Sorts the `n` vec4 positions in `positions` into `cells` cells. Afterwards out.keys and
  /// out.order hold the sorted keys and permutation and out.start the cells' first particles
  /// (cells + 1 entries). The positions themselves are not moved: gather() does that.
  void sort(const Buffer& positions, std::size_t n, std::size_t cells, SortedCells& out);
  /// Rebuilds only out.start from out.keys (n already sorted keys).
  void cell_starts(std::size_t n, std::size_t cells, SortedCells& out);
  /// out_k[i] = in_k[order[i]] for up to four vec4 arrays, and optionally one uint array.
  void gather(const Buffer& order, std::size_t n, const std::vector<const Buffer*>& in,
              const std::vector<Buffer*>& out, const Buffer* uint_in = nullptr, Buffer* uint_out = nullptr);
  /// Exclusive prefix sum of `m` uints in place.
  void exclusive_scan(Buffer& data, std::size_t m) { scan(data, m, 0); }

 private:
  void scan(Buffer& data, std::size_t m, std::size_t level);
  ComputeProgram count_, scatter_, order_, scan_block_, scan_add_, cell_count_;
  ComputeProgram gather_[4], gather_uint_[4];
  Buffer keys_tmp_, vals_tmp_, unordered_;
  std::vector<Buffer> scan_sums_;
};

}  // namespace rtsph::gpu
