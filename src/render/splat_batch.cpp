#include "render/splat_batch.h"

#include <algorithm>
#include <cmath>

namespace rtsph::render {

void SplatBatch::build(const float* x, const float* y, const float* z, std::size_t n,
                       float spacing) {
  size_ = merged_ = 0;
  auto emit_all = [&] {
    out_.resize(4 * n);
    std::copy(x, x + n, out_.begin());
    std::copy(y, y + n, out_.begin() + n);
    if (z) std::copy(z, z + n, out_.begin() + 2 * n);
    else std::fill(out_.begin() + 2 * n, out_.begin() + 3 * n, 0.0f);
    std::fill(out_.begin() + 3 * n, out_.end(), 1.0f);
    size_ = n;
  };
  if (!z || n == 0 || !(spacing > 0)) return emit_all();

  // Cubes of two spacings over the fluid's bounds, with one empty layer around them.
  float lo[3] = {x[0], y[0], z[0]}, hi[3] = {x[0], y[0], z[0]};
  const float* p[3] = {x, y, z};
  bool finite = true;  // a NaN would slip past min/max and index nowhere
  for (int k = 0; k < 3; ++k)
    for (std::size_t i = 0; i < n; ++i) {
      lo[k] = std::min(lo[k], p[k][i]);
      hi[k] = std::max(hi[k], p[k][i]);
      finite = finite && std::isfinite(p[k][i]);
    }
  if (!finite) return emit_all();
  const float cube = 2 * spacing;
  long dim[3];
  double cells = 1;
  for (int k = 0; k < 3; ++k) {
    dim[k] = static_cast<long>((hi[k] - lo[k]) / cube) + 3;
    cells *= double(dim[k]);
  }
  // A few particles flung far apart would need a huge grid; nothing worth merging then.
  if (cells > 8.0 * double(n) + 4096) return emit_all();
  const std::size_t nc = static_cast<std::size_t>(cells);
  count_.assign(nc, 0);
  cell_of_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    long c[3];
    for (int k = 0; k < 3; ++k)
      c[k] = std::clamp(static_cast<long>((p[k][i] - lo[k]) / cube) + 1, 1L, dim[k] - 2);
    const long id = (c[2] * dim[1] + c[1]) * dim[0] + c[0];
    cell_of_[i] = static_cast<std::int32_t>(id);
    if (count_[id] < 0xffff) ++count_[id];
  }
  // Interior: full, and so are all 26 neighbours (erosion of the full set by a 3×3×3 cube, one
  // axis at a time).
  full_.resize(nc);
  tmp_.resize(nc);
  for (std::size_t c = 0; c < nc; ++c) full_[c] = count_[c] >= kFull;
  const long stride[3] = {1, dim[0], dim[0] * dim[1]};
  for (int k = 0; k < 3; ++k) {
    for (std::size_t c = 0; c < nc; ++c) {
      const long ci = static_cast<long>(c);
      const long a = (ci / stride[k]) % dim[k];
      tmp_[c] = a > 0 && a < dim[k] - 1 && full_[c] && full_[c - stride[k]] && full_[c + stride[k]];
    }
    full_.swap(tmp_);
  }
  // Merged cubes first (their order follows the cubes'), then the particles that stay.
  slot_.assign(nc, -1);
  sum_.assign(3 * nc, 0.0f);
  std::size_t m = 0, keep = 0;
  for (std::size_t c = 0; c < nc; ++c)
    if (full_[c]) slot_[c] = static_cast<std::int32_t>(m++);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t c = static_cast<std::size_t>(cell_of_[i]);
    if (full_[c])
      for (int k = 0; k < 3; ++k) sum_[3 * c + k] += p[k][i];
    else
      ++keep;
  }
  size_ = m + keep;
  merged_ = m;
  out_.resize(4 * size_);
  float* o[4] = {out_.data(), out_.data() + size_, out_.data() + 2 * size_, out_.data() + 3 * size_};
  for (std::size_t c = 0; c < nc; ++c) {
    if (!full_[c]) continue;
    const std::size_t j = static_cast<std::size_t>(slot_[c]);
    const float k = float(count_[c]);
    for (int a = 0; a < 3; ++a) o[a][j] = sum_[3 * c + a] / k;
    o[3][j] = k;
  }
  std::size_t j = m;
  for (std::size_t i = 0; i < n; ++i) {
    if (full_[static_cast<std::size_t>(cell_of_[i])]) continue;
    for (int a = 0; a < 3; ++a) o[a][j] = p[a][i];
    o[3][j++] = 1.0f;
  }
}

}  // namespace rtsph::render
