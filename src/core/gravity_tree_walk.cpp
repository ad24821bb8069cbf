// Octree walk (gravity_tree.h): one interaction list per group, then every particle of the
// group sums the list's multipoles and particles, 8 lanes at a time, in double.
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/gravity_kernel.h"
#include "core/gravity_tree.h"

namespace rtsph {
namespace {

using simd::f8;
using simd::i8;
using gravity_detail::DoubleLanes;

// Padding lanes: massless, far away (finite, so no inf or NaN reaches the sums), h = 1.
constexpr float kFar = 3e18f;

std::size_t padded(std::size_t n) { return (n + simd::kWidth - 1) / simd::kWidth * simd::kWidth; }

float gap2(const float* c0, const float* h0, const float* c1, const float* h1) {
  float g2 = 0;
  for (int a = 0; a < 3; ++a) {
    const float g = std::max(0.0f, std::fabs(c0[a] - c1[a]) - (h0[a] + h1[a]));
    g2 += g * g;
  }
  return g2;
}

}  // namespace

void GravityTree::walk_group(const Group& g, Scratch& s) const {
  const float zero[3] = {0, 0, 0};
  s.node_ids.clear();
  s.leaf_ids.clear();
  const uint32_t nn = uint32_t(walk_.size());
  for (uint32_t k = 0; k < nn;) {
    const WalkNode& nd = walk_[k];
    // Open (a) while the boxes come within 2·max(h): softened pairs are summed particle by
    // particle (this also opens every node that contains or touches the group); (b) while the
    // group's nearest point lies within the node's opening radius around its com.
    const float soft = 2 * std::max(g.hmax, nd.hmax);
    const bool open = (gap2(g.centre, g.half, nd.centre, nd.half) <= soft * soft) |
                      (gap2(g.centre, g.half, nd.com, zero) < nd.open2);
    if (!(nd.mass > 0)) {  // test particles only: no field
      k = nd.next;
    } else if (!open) {
      s.node_ids.push_back(k);
      k = nd.next;
    } else {
      if (nd.next == k + 1) s.leaf_ids.push_back(k);
      ++k;
    }
  }
  const std::size_t nodes = s.node_ids.size(), np = padded(nodes);
  for (auto& a : s.node) a.resize(std::max(a.size(), np));
  for (std::size_t l = 0; l < np; ++l) {
    if (l < nodes) {
      const float* v = multipoles_[s.node_ids[l]].v;
      for (int t = 0; t < 10; ++t) s.node[t][l] = v[t];
    } else {
      for (int a = 0; a < 3; ++a) s.node[a][l] = kFar;
      for (int t = 3; t < 10; ++t) s.node[t][l] = 0;
    }
  }
  std::size_t parts = 0;
  for (uint32_t k : s.leaf_ids) parts += nodes_[k].count;
  const std::size_t pp = padded(parts);
  for (auto& a : s.part) a.resize(std::max(a.size(), pp));
  s.index.resize(std::max(s.index.size(), pp));
  std::size_t l = 0;
  for (uint32_t k : s.leaf_ids) {
    for (uint32_t i = nodes_[k].begin, e = i + nodes_[k].count; i < e; ++i, ++l) {
      for (int a = 0; a < 3; ++a) s.part[a][l] = x_[a][i];
      s.part[3][l] = m_[i];
      s.part[4][l] = inv_h_[i];
      s.index[l] = int32_t(i);
    }
  }
  for (; l < pp; ++l) {
    for (int a = 0; a < 3; ++a) s.part[a][l] = kFar;
    s.part[3][l] = 0;
    s.part[4][l] = 1;
    s.index[l] = -1;
  }
  s.node_terms += double(nodes) * g.count;
  s.part_terms += double(parts) * g.count;
  s.part_count = parts;
}

// Multipole of a node at r = x - com (Newtonian: accepted nodes lie beyond every softening):
//   Φ = -G [M/r + ½ rᵀQr / r⁵],  a = -∇Φ = G [-M r/r³ + Q r/r⁵ - (5/2)(rᵀQr) r/r⁷].
template <bool Pot>
void GravityTree::sum_group(const Group& g, double G, const Scratch& s, float* const acc[3],
                            float* pot) const {
  const std::size_t nb = padded(s.node_ids.size()), pb = padded(s.part_count);
  for (uint32_t t = g.begin; t < g.begin + g.count; ++t) {
    f8 xi[3];
    for (int a = 0; a < 3; ++a) xi[a] = simd::splat(x_[a][t]);
    DoubleLanes sum[3], phi;
    for (std::size_t b0 = 0; b0 < nb; b0 += gravity_detail::kBlock * simd::kWidth) {
      const std::size_t b1 = std::min(nb, b0 + gravity_detail::kBlock * simd::kWidth);
      f8 part[3] = {}, ppart = {};
      for (std::size_t b = b0; b < b1; b += simd::kWidth) {
        f8 r[3], q[6];
        for (int a = 0; a < 3; ++a) r[a] = xi[a] - simd::load(s.node[a].data() + b);
        const f8 mass = simd::load(s.node[3].data() + b);
        for (int k = 0; k < 6; ++k) q[k] = simd::load(s.node[4 + k].data() + b);
        const f8 r2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
        const f8 inv_r = simd::rsqrt(r2), inv_r2 = inv_r * inv_r;
        const f8 inv_r3 = inv_r * inv_r2, inv_r5 = inv_r3 * inv_r2;
        const f8 qr[3] = {q[0] * r[0] + q[1] * r[1] + q[2] * r[2],
                          q[1] * r[0] + q[3] * r[1] + q[4] * r[2],
                          q[2] * r[0] + q[4] * r[1] + q[5] * r[2]};
        const f8 rqr = r[0] * qr[0] + r[1] * qr[1] + r[2] * qr[2];
        const f8 radial = -mass * inv_r3 - 2.5f * rqr * inv_r5 * inv_r2;
        for (int a = 0; a < 3; ++a) part[a] += radial * r[a] + qr[a] * inv_r5;
        if constexpr (Pot) ppart += -mass * inv_r - 0.5f * rqr * inv_r5;
      }
      for (int a = 0; a < 3; ++a) sum[a].add(part[a]);
      if constexpr (Pot) phi.add(ppart);
    }
    const f8 inv_hi = simd::splat(inv_h_[t]);
    const i8 self = i8{} + int32_t(t);
    for (std::size_t b0 = 0; b0 < pb; b0 += gravity_detail::kBlock * simd::kWidth) {
      const std::size_t b1 = std::min(pb, b0 + gravity_detail::kBlock * simd::kWidth);
      f8 part[3] = {}, ppart = {};
      for (std::size_t b = b0; b < b1; b += simd::kWidth) {
        f8 xj[3];
        for (int a = 0; a < 3; ++a) xj[a] = simd::load(s.part[a].data() + b);
        i8 idx;
        __builtin_memcpy(&idx, s.index.data() + b, sizeof idx);
        const i8 valid = (idx != self) & (idx >= 0);
        gravity_detail::accumulate_pairs<3, Pot>(xi, xj, simd::load(s.part[3].data() + b), inv_hi,
                                                 simd::load(s.part[4].data() + b), valid, part,
                                                 &ppart);
      }
      for (int a = 0; a < 3; ++a) sum[a].add(part[a]);
      if constexpr (Pot) phi.add(ppart);
    }
    const uint32_t j = order_[t];
    for (int a = 0; a < 3; ++a) acc[a][j] = float(G * sum[a].sum());
    if constexpr (Pot) pot[j] = float(G * phi.sum());
  }
}

void GravityTree::accelerations(double G, double theta, float* const acc[3], float* pot,
                                const ThreadPool& pool) {
  if (n_ == 0) return;
  // Chunks of groups, each with its own list buffers; the chunking never changes a result,
  // since a particle's sum depends only on its group's list.
  const std::size_t groups = groups_.size();
  const std::size_t chunks = std::min<std::size_t>(groups, std::size_t(pool.threads()) * 8);
  if (scratch_.size() < chunks) scratch_.resize(chunks);
  // Opening radius around the com, squared, for this θ (θ = 0: every node is opened): l/θ
  // (Barnes & Hut 1986), and never less than the distance from the com to the farthest corner
  // of the node's box, δ + (√3/2)·l, so no accepted node contains a target however far its
  // mass sits off-centre (the failure Barnes 1994 and Salmon & Warren 1994 point out).
  const float inv_theta = theta > 0 ? float(1.0 / theta) : 0.0f;
  walk_.resize(nodes_.size());
  pool.parallel_for(nodes_.size(), [&](std::size_t b, std::size_t e) {
    for (std::size_t k = b; k < e; ++k) {
      const Node& nd = nodes_[k];
      WalkNode& w = walk_[k];
      const float r_open = std::max(nd.size * inv_theta, nd.offset + 0.8660254f * nd.size);
      w.open2 = theta > 0 ? r_open * r_open : std::numeric_limits<float>::infinity();
      for (int a = 0; a < 3; ++a) {
        w.centre[a] = nd.centre[a];
        w.half[a] = nd.half[a];
        w.com[a] = nd.com[a];
      }
      w.hmax = nd.hmax;
      w.mass = nd.mass;
      w.next = nd.next;
    }
  });
  pool.parallel_for(chunks, [&](std::size_t cb, std::size_t ce) {
    for (std::size_t c = cb; c < ce; ++c) {
      Scratch& s = scratch_[c];
      s.node_terms = s.part_terms = 0;
      for (std::size_t k = groups * c / chunks; k < groups * (c + 1) / chunks; ++k) {
        walk_group(groups_[k], s);
        if (pot) sum_group<true>(groups_[k], G, s, acc, pot);
        else sum_group<false>(groups_[k], G, s, acc, pot);
      }
    }
  }, 1);
  double nodes = 0, parts = 0;
  for (std::size_t c = 0; c < chunks; ++c) {
    nodes += scratch_[c].node_terms;
    parts += scratch_[c].part_terms;
  }
  mean_nodes_ = nodes / double(n_);
  mean_parts_ = parts / double(n_);
}

}  // namespace rtsph
