#include "gpu/sort.h"

#include <stdexcept>

#include <fmt/format.h>

#include "gpu/layout.h"

namespace rtsph::gpu {

namespace {
std::vector<std::string> with(std::vector<std::string> d, const std::string& extra) {
  d.push_back(extra);
  return d;
}
GLuint blocks_of(std::size_t n) { return GLuint((n + RTSPH_WG - 1) / RTSPH_WG); }
}  // namespace

CellSorter::CellSorter(const std::vector<std::string>& defines)
    : count_("cell_sort_count.comp", defines),
      scatter_("cell_sort_scatter.comp", defines),
      order_("cell_sort_order.comp", defines),
      scan_block_("scan_block.comp", defines),
      scan_add_("scan_add.comp", defines),
      cell_count_("cell_count.comp", defines) {
  // Sized once: the recursion holds references into it. Four levels scan 256^4 values.
  scan_sums_.resize(4);
  for (int c = 0; c < 4; ++c) {
    gather_[c] = ComputeProgram("gather.comp", with(defines, fmt::format("COUNT {}", c + 1)));
    if (c < 3)
      gather_uint_[c] = ComputeProgram("gather.comp", with(with(defines, fmt::format("COUNT {}", c + 1)), "GATHER_UINT"));
  }
}

// A counting sort: cells counted (atomics that only count, and a provisional rank), an
// exclusive scan of the counts (which is also the start array), a scatter to the provisional
// slots, and each cell put in the order of the particles' previous indices. Five dispatches and
// the scan's two or three, where the radix sort it replaced took ~20 (a dispatch costs ~20 µs
// on an H100 under GL even with no work; docs/performance.md).
void CellSorter::sort(const Buffer& positions, std::size_t n, std::size_t cells, SortedCells& out) {
  const std::size_t bytes = std::max<std::size_t>(n, 1) * 4;
  out.keys.reserve(bytes);
  out.order.reserve(bytes);
  keys_tmp_.reserve(bytes);
  vals_tmp_.reserve(bytes);
  unordered_.reserve(bytes);
  out.start.reserve((cells + 1) * 4);
  out.start.fill_zero();
  if (n > 0) {
    positions.bind(RTSPH_B_GATHER_IN0);
    keys_tmp_.bind(RTSPH_B_KEYS_IN);
    vals_tmp_.bind(RTSPH_B_VALS_IN);
    out.start.bind(RTSPH_B_SCAN);
    count_.set("n", GLuint(n));
    count_.dispatch(n);
  }
  scan(out.start, cells + 1, 0);
  if (n == 0) return;
  keys_tmp_.bind(RTSPH_B_KEYS_IN);
  vals_tmp_.bind(RTSPH_B_VALS_IN);
  out.start.bind(RTSPH_B_SCAN);
  out.keys.bind(RTSPH_B_KEYS_OUT);
  unordered_.bind(RTSPH_B_VALS_OUT);
  scatter_.set("n", GLuint(n));
  scatter_.dispatch(n);
  out.keys.bind(RTSPH_B_KEYS_OUT);
  unordered_.bind(RTSPH_B_VALS_OUT);
  out.start.bind(RTSPH_B_SCAN);
  out.order.bind(RTSPH_B_COUNTS);
  order_.set("n", GLuint(n));
  order_.dispatch(n);
}

void CellSorter::cell_starts(std::size_t n, std::size_t cells, SortedCells& out) {
  out.start.reserve((cells + 1) * 4);
  out.start.fill_zero();
  if (n > 0) {
    out.keys.bind(RTSPH_B_KEYS_IN);
    out.start.bind(RTSPH_B_SCAN);
    cell_count_.set("n", GLuint(n));
    cell_count_.dispatch(n);
  }
  scan(out.start, cells + 1, 0);
}

void CellSorter::scan(Buffer& data, std::size_t m, std::size_t level) {
  if (m == 0) return;
  const GLuint blocks = blocks_of(m);
  if (level >= scan_sums_.size()) throw std::length_error("exclusive_scan: more than 256^4 values");
  scan_sums_[level].reserve(std::size_t(blocks) * 4);
  data.bind(RTSPH_B_SCAN);
  scan_sums_[level].bind(RTSPH_B_SCAN_SUMS);
  scan_block_.set("n", GLuint(m));
  scan_block_.dispatch_groups(blocks);
  if (blocks == 1) return;
  scan(scan_sums_[level], blocks, level + 1);
  data.bind(RTSPH_B_SCAN);
  scan_sums_[level].bind(RTSPH_B_SCAN_SUMS);
  scan_add_.set("n", GLuint(m));
  scan_add_.dispatch_groups(blocks);
}

void CellSorter::gather(const Buffer& order, std::size_t n, const std::vector<const Buffer*>& in,
                        const std::vector<Buffer*>& out, const Buffer* uint_in, Buffer* uint_out) {
  if (n == 0 || in.empty()) return;
  order.bind(RTSPH_B_VALS_IN);
  for (std::size_t k = 0; k < in.size(); ++k) {
    in[k]->bind(GLuint(RTSPH_B_GATHER_IN0 + k));
    out[k]->bind(GLuint(RTSPH_B_GATHER_OUT0 + k));
  }
  const ComputeProgram* prog = &gather_[in.size() - 1];
  if (uint_in) {
    uint_in->bind(RTSPH_B_GATHER_IN3);
    uint_out->bind(RTSPH_B_GATHER_OUT3);
    prog = &gather_uint_[in.size() - 1];
  }
  prog->set("n", GLuint(n));
  prog->dispatch(n);
}

}  // namespace rtsph::gpu
