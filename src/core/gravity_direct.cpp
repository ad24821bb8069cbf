#include "core/gravity_direct.h"

#include <algorithm>

#include "core/gravity_kernel.h"

namespace rtsph {
namespace {

using simd::f8;
using simd::i8;
using gravity_detail::DoubleLanes;

// One row: particle i against all j in index order, 8 at a time; the last partial batch is
// copied into padded lanes (massless, h = 1) so the loads never run past the caller's arrays.
template <int D, bool Pot>
void row(const GravitySources<D>& s, std::size_t i, double G, float* const acc[D], float* pot) {
  f8 xi[D];
  for (int a = 0; a < D; ++a) xi[a] = simd::splat(s.x[a][i]);
  // 1/h exactly (IEEE division) on both sides of a pair, so the pair term is antisymmetric.
  const f8 inv_hi = simd::splat(1.0f / s.h[i]);
  DoubleLanes sum[D], phi;
  const std::size_t full = s.n / simd::kWidth * simd::kWidth;
  const i8 lanes = simd::lane_index();
  for (std::size_t j0 = 0; j0 < full; j0 += gravity_detail::kBlock * simd::kWidth) {
    const std::size_t j1 = std::min(full, j0 + gravity_detail::kBlock * simd::kWidth);
    f8 part[D] = {}, ppart = {};
    for (std::size_t j = j0; j < j1; j += simd::kWidth) {
      f8 xj[D];
      for (int a = 0; a < D; ++a) xj[a] = simd::load(s.x[a] + j);
      const i8 valid = lanes != int(i - j);  // the self-pair lane when i is in this batch
      gravity_detail::accumulate_pairs<D, Pot>(xi, xj, simd::load(s.m + j), inv_hi,
                                               1.0f / simd::load(s.h + j), valid, part, &ppart);
    }
    for (int a = 0; a < D; ++a) sum[a].add(part[a]);
    if constexpr (Pot) phi.add(ppart);
  }
  if (full < s.n) {
    alignas(32) float x[D][simd::kWidth] = {}, m[simd::kWidth] = {}, h[simd::kWidth];
    for (int l = 0; l < simd::kWidth; ++l) h[l] = 1.0f;
    for (std::size_t j = full; j < s.n; ++j) {
      for (int a = 0; a < D; ++a) x[a][j - full] = s.x[a][j];
      m[j - full] = s.m[j];
      h[j - full] = s.h[j];
    }
    f8 xj[D], part[D] = {}, ppart = {};
    for (int a = 0; a < D; ++a) xj[a] = simd::load(x[a]);
    const i8 valid = (lanes < int(s.n - full)) & (lanes != int(i - full));
    gravity_detail::accumulate_pairs<D, Pot>(xi, xj, simd::load(m), inv_hi, 1.0f / simd::load(h),
                                             valid, part, &ppart);
    for (int a = 0; a < D; ++a) sum[a].add(part[a]);
    if constexpr (Pot) phi.add(ppart);
  }
  for (int a = 0; a < D; ++a) acc[a][i] = float(G * sum[a].sum());
  if constexpr (Pot) pot[i] = float(G * phi.sum());
}

}  // namespace

template <int D>
void gravity_direct(const GravitySources<D>& src, double G, float* const acc[D], float* pot,
                    const ThreadPool& pool) {
  // A row costs N pairs (~N ns), so even a few dozen rows are worth a thread.
  const std::size_t grain = 32;
  pool.parallel_for(src.n, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      if (pot) row<D, true>(src, i, G, acc, pot);
      else row<D, false>(src, i, G, acc, pot);
    }
  }, grain);
}

template void gravity_direct<2>(const GravitySources<2>&, double, float* const[2], float*,
                                const ThreadPool&);
template void gravity_direct<3>(const GravitySources<3>&, double, float* const[3], float*,
                                const ThreadPool&);

}  // namespace rtsph
