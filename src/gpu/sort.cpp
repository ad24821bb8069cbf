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
    : keys_("keys.comp", defines),
      count_("radix_count.comp", defines),
      scatter_("radix_scatter.comp", defines),
      scan_block_("scan_block.comp", defines),
      scan_add_("scan_add.comp", defines),
      cell_count_("cell_count.comp", defines) {
  static_assert(RTSPH_WG == RTSPH_RADIX, "radix_count.comp gives each digit one thread");
  // Sized once: the recursion holds references into it. Four levels scan 256^4 values.
  scan_sums_.resize(4);
  for (int c = 0; c < 4; ++c) {
    gather_[c] = ComputeProgram("gather.comp", with(defines, fmt::format("COUNT {}", c + 1)));
    if (c < 3)
      gather_uint_[c] = ComputeProgram("gather.comp", with(with(defines, fmt::format("COUNT {}", c + 1)), "GATHER_UINT"));
  }
}

void CellSorter::sort(const Buffer& positions, std::size_t n, std::size_t cells, SortedCells& out) {
  const std::size_t bytes = std::max<std::size_t>(n, 1) * 4;
  out.keys.reserve(bytes);
  out.order.reserve(bytes);
  keys_tmp_.reserve(bytes);
  vals_tmp_.reserve(bytes);
  if (n > 0) {
    positions.bind(RTSPH_B_GATHER_IN0);
    out.keys.bind(RTSPH_B_KEYS_IN);
    out.order.bind(RTSPH_B_VALS_IN);
    keys_.set("n", GLuint(n));
    keys_.dispatch(n);
    // Digits needed for the largest key, cells - 1.
    int passes = 0;
    for (std::size_t top = cells > 0 ? cells - 1 : 0; top > 0; top >>= RTSPH_RADIX_BITS) ++passes;
    const GLuint blocks = blocks_of(n);
    counts_.reserve(std::size_t(RTSPH_RADIX) * blocks * 4);
    for (int pass = 0; pass < passes; ++pass) {
      // Ping-pong: even passes read out.*, odd passes read the scratch pair.
      Buffer& kin = pass % 2 == 0 ? out.keys : keys_tmp_;
      Buffer& vin = pass % 2 == 0 ? out.order : vals_tmp_;
      Buffer& kout = pass % 2 == 0 ? keys_tmp_ : out.keys;
      Buffer& vout = pass % 2 == 0 ? vals_tmp_ : out.order;
      const GLuint shift = GLuint(pass * RTSPH_RADIX_BITS);
      kin.bind(RTSPH_B_KEYS_IN);
      counts_.bind(RTSPH_B_COUNTS);
      count_.set("n", GLuint(n));
      count_.set("shift", shift);
      count_.set("blocks", blocks);
      count_.dispatch_groups(blocks);
      scan(counts_, std::size_t(RTSPH_RADIX) * blocks, 0);
      kin.bind(RTSPH_B_KEYS_IN);
      vin.bind(RTSPH_B_VALS_IN);
      kout.bind(RTSPH_B_KEYS_OUT);
      vout.bind(RTSPH_B_VALS_OUT);
      counts_.bind(RTSPH_B_COUNTS);
      scatter_.set("n", GLuint(n));
      scatter_.set("shift", shift);
      scatter_.set("blocks", blocks);
      scatter_.dispatch_groups(blocks);
    }
    if (passes % 2 == 1) {
      out.keys.swap(keys_tmp_);
      out.order.swap(vals_tmp_);
    }
  }
  cell_starts(n, cells, out);
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
