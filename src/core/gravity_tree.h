#pragma once
// Barnes & Hut 1986 octree for kernel-softened self-gravity, 3D. O(N log N) against the O(N²)
// of gravity_direct.h, with the same pair force where it sums pairs.
//
// Build (deterministic, independent of the thread count): 63-bit Morton keys of the positions
// in the bounding cube, a stable LSD radix sort, then nodes top-down over the sorted keys in
// depth-first order with a skip pointer (`next`), so traversal needs no stack. Moments bottom-up:
// mass, centre of mass and the traceless quadrupole Q = Σ m (3 d dᵀ - |d|² I) about it.
//
// Walk: per group (up to `group_size` particles of one node or of adjacent sibling nodes), one
// interaction list serves all its particles. A node is accepted as a multipole when (a) the
// distance from its centre of mass to the group's box exceeds max(l/θ, δ + (√3/2)·l) (l: largest
// side of the node's box, δ: offset of the centre of mass from the box centre; the second term
// keeps every target outside the node however off-centre its mass, cf. Barnes 1994) and (b) the
// gap between the node's box and the group's box exceeds 2·max(h) of both, so every softened
// pair (r < 2 max(hᵢ, hⱼ)) is summed particle by particle with the symmetric softening, exactly
// as in direct summation. Otherwise it is opened; opened leaves add their particles to the list.
// Each particle sums its lists in a fixed order (float blocks into double): bitwise identical
// for any thread count. Buffers grow geometrically and are reused: no allocation after the
// first build of a given size.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/aligned_array.h"
#include "core/gravity_direct.h"
#include "core/parallel.h"

namespace rtsph {

class GravityTree {
 public:
  struct Options {
    // Measured on a Plummer sphere at 10⁴-10⁵ (docs/performance.md): leaves of 8-16 and groups
    // of 32-64 are within noise of each other; larger groups share a walk among more particles
    // but lengthen every particle's list.
    unsigned leaf_size = 16;   // particles per leaf at most (unless they share a Morton cell)
    unsigned group_size = 64;  // particles sharing one interaction list at most
  };
  struct Node {
    float com[3], mass;
    float quad[6];            // xx, xy, xz, yy, yz, zz, about com
    float centre[3], half[3];  // tight box of the node's particles
    float hmax, size, offset;  // max h, largest box side l, |com - centre| = δ
    uint32_t begin, count;     // particle range in sorted order
    uint32_t next;             // first node after this subtree; next == own index + 1: a leaf
  };

  /// Particles [begin, begin + count) in Morton order share one interaction list.
  struct Group {
    uint32_t begin, count;
    float centre[3] = {}, half[3] = {}, hmax = 0;  // tight box and max h of the particles
  };

  /// Builds the tree of `src` (3D positions, masses, h > 0). The arrays must stay valid until
  /// the last accelerations() call of this build.
  void build(const GravitySources<3>& src, const ThreadPool& pool, Options opt);
  void build(const GravitySources<3>& src, const ThreadPool& pool) { build(src, pool, Options{}); }

  /// acc[a][i] (m/s²) and, when pot is not null, pot[i] (J/kg), in the caller's particle order.
  /// θ is the opening angle (smaller: more accurate, slower).
  void accelerations(double G, double theta, float* const acc[3], float* pot,
                     const ThreadPool& pool);

  std::size_t node_count() const { return nodes_.size(); }
  const std::vector<Node>& nodes() const { return nodes_; }
  /// Multipole and particle interactions per particle in the last accelerations() call.
  double mean_node_interactions() const { return mean_nodes_; }
  double mean_particle_interactions() const { return mean_parts_; }
  /// Bytes held by the tree and its scratch (capacity, not size).
  std::size_t memory_bytes() const;

 private:
  // One group's interaction list, reused by every group of one chunk: accepted nodes as SoA
  // (com x, y, z, mass, quad[6]) and opened leaves' particles (x, y, z, m, 1/h and index), both
  // padded to whole 8-lane batches.
  struct Scratch {
    std::vector<uint32_t> node_ids, leaf_ids;
    AlignedArray<float> node[10], part[5];
    AlignedArray<int32_t> index;
    std::size_t part_count = 0;             // particles in the list (index holds them padded)
    double node_terms = 0, part_terms = 0;  // interactions summed, for the statistics
    std::size_t bytes() const {
      std::size_t b = (node_ids.capacity() + leaf_ids.capacity()) * 4 + index.bytes();
      for (const auto& a : node) b += a.bytes();
      for (const auto& a : part) b += a.bytes();
      return b;
    }
  };
  void walk_group(const Group& g, Scratch& s) const;
  template <bool Pot>
  void sum_group(const Group& g, double G, const Scratch& s, float* const acc[3], float* pot) const;
  uint32_t build_node(uint32_t begin, uint32_t end, int level, bool grouped);
  void compute_moments();
  void sort_keys(std::size_t n);

  Options opt_;
  std::size_t n_ = 0;
  AlignedArray<uint64_t> keys_, keys_tmp_;
  AlignedArray<uint32_t> order_, order_tmp_;
  AlignedArray<float> x_[3], m_, h_, inv_h_;  // particles in Morton order; 1/h for the pairs
  std::vector<Node> nodes_;
  // What the walk reads of each node, packed (52 of Node's 88 bytes: at 10⁶ particles the walk
  // streams ~12 MB per group instead of ~20), with the squared opening radius for the θ of the
  // last accelerations() call.
  struct WalkNode {
    float centre[3], half[3], com[3], hmax, open2, mass;
    uint32_t next;
  };
  std::vector<WalkNode> walk_;
  // What an interaction list copies of an accepted node: com x, y, z, mass, quad[6].
  struct Multipole {
    float v[10];
  };
  std::vector<Multipole> multipoles_;
  std::vector<Group> groups_;
  std::vector<Scratch> scratch_;
  std::vector<uint32_t> radix_count_;
  double mean_nodes_ = 0, mean_parts_ = 0;
};

}  // namespace rtsph
