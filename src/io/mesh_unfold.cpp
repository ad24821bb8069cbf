// Edge flips that undo folded triangles in a closed mesh (SurfaceMesh, surface.h).
//
// OpenVDB's adaptive volume-to-mesh merges flat regions into large polygons. Where a merged
// region meets a finer one it fans slivers, and a sliver across a slightly uneven flat face can
// come out folded: wound against the surface, its face normal opposite its vertex normals (a dark
// line in a render; eight of them on the side faces of a settled 16³ block at adaptivity 0.5, and
// whole quads split along the wrong diagonal). A fold and its neighbour across one edge span a
// quadrilateral; replacing the shared edge by the other diagonal unfolds it when both new
// triangles face outwards, or leaves a lesser fold that a next flip can undo. An edge flip keeps
// every vertex, closedness and winding.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

#include "io/surface.h"

namespace rtsph::io {
namespace {

using Tri = std::array<std::uint32_t, 3>;

std::uint64_t key(std::uint32_t a, std::uint32_t b) { return (std::uint64_t(a) << 32) | b; }

}  // namespace

std::size_t unfold_triangles(SurfaceMesh& m) {
  const std::size_t count = m.triangle_count();
  auto tri = [&](std::size_t t) { return Tri{m.triangles[3 * t], m.triangles[3 * t + 1], m.triangles[3 * t + 2]}; };
  // The least cosine between the unit face normal of (a, b, c) and its vertices' normals; -2
  // for a degenerate triangle (no face normal).
  auto facing = [&](const Tri& t) {
    const float* p = m.points.data();
    double e1[3], e2[3], f[3];
    for (int k = 0; k < 3; ++k) {
      e1[k] = double(p[3 * t[1] + k]) - p[3 * t[0] + k];
      e2[k] = double(p[3 * t[2] + k]) - p[3 * t[0] + k];
    }
    f[0] = e1[1] * e2[2] - e1[2] * e2[1];
    f[1] = e1[2] * e2[0] - e1[0] * e2[2];
    f[2] = e1[0] * e2[1] - e1[1] * e2[0];
    const double len = std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    if (!(len > 0)) return -2.0;
    double least = 1;
    for (const std::uint32_t v : t) {
      const float* n = &m.normals[3 * v];
      least = std::min(least, (f[0] * n[0] + f[1] * n[1] + f[2] * n[2]) / len);
    }
    return least;
  };
  // Directed edge -> the triangle that runs it (closed and consistently wound: one each), kept
  // for the triangles that touch a fold's vertices only: every edge a flip looks up or creates
  // has one of those vertices as an end, so a mesh of millions of triangles with a handful of
  // folds maps a few dozen edges, and one without folds none.
  std::unordered_map<std::uint64_t, std::uint32_t> edge;
  auto set = [&](std::size_t t, const Tri& v) {
    for (int k = 0; k < 3; ++k) {
      m.triangles[3 * t + k] = v[k];
      edge[key(v[k], v[(k + 1) % 3])] = std::uint32_t(t);
    }
  };
  // A few passes, the worst folds first (a quad split along the wrong diagonal is a full fold,
  // and its own flip must come before a sliver's next to it takes the edge): one flip can leave
  // the neighbour's other edge to flip next.
  std::vector<std::pair<double, std::size_t>> folds;
  std::unordered_set<std::uint32_t> near;  // the folds' vertices
  for (int pass = 0;; ++pass) {
    folds.clear();
    for (std::size_t t = 0; t < count; ++t)
      if (const double q = facing(tri(t)); q <= 0) folds.emplace_back(q, t);
    if (folds.empty() || pass == 4) return folds.size();
    std::sort(folds.begin(), folds.end());
    near.clear();
    for (const auto& f : folds)
      for (const std::uint32_t v : tri(f.second)) near.insert(v);
    edge.clear();
    for (std::size_t t = 0; t < count; ++t) {
      const Tri v = tri(t);
      if (near.count(v[0]) || near.count(v[1]) || near.count(v[2]))
        for (int k = 0; k < 3; ++k) edge[key(v[k], v[(k + 1) % 3])] = std::uint32_t(t);
    }
    bool changed = false;
    for (const auto& [_, t] : folds) {
      const Tri v = tri(t);
      const double own = facing(v);
      if (own > 0) continue;  // unfolded by an earlier flip this pass
      // The flip that leaves the pair's worse triangle best, if that is better than before: a
      // full fold can take two flips, the first leaving a sliver that the second unfolds.
      double best = -3;
      std::size_t best_u = 0;
      Tri best_a{}, best_b{};
      for (int k = 0; k < 3; ++k) {
        // t = (a, b, c) and its neighbour u = (b, a, d) across a-b: the quadrilateral a-d-b-c,
        // split along c-d instead, is (a, d, c) and (d, b, c).
        const std::uint32_t a = v[k], b = v[(k + 1) % 3], c = v[(k + 2) % 3];
        const auto it = edge.find(key(b, a));
        if (it == edge.end()) continue;
        const std::size_t u = it->second;
        const Tri w = tri(u);
        std::uint32_t d = w[0];
        for (const std::uint32_t x : w)
          if (x != a && x != b) d = x;
        if (d == c || edge.count(key(c, d)) || edge.count(key(d, c))) continue;  // c-d already an edge
        const Tri na{a, d, c}, nb{d, b, c};
        const double q = std::min(facing(na), facing(nb));
        if (q > best && q > std::min(own, facing(w))) best = q, best_u = u, best_a = na, best_b = nb;
      }
      if (best == -3) continue;
      const Tri w = tri(best_u);
      for (int k = 0; k < 3; ++k) {
        edge.erase(key(v[k], v[(k + 1) % 3]));
        edge.erase(key(w[k], w[(k + 1) % 3]));
      }
      set(t, best_a);
      set(best_u, best_b);
      changed = true;
    }
    if (!changed) return folds.size();  // no flip: the folds found are the ones left
  }
}

}  // namespace rtsph::io
