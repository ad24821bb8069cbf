#pragma once
// What the surface's splat pass draws (surface_pass.h): one splat per fluid particle near the
// surface, one per block of interior. On a software rasteriser each point costs a fixed setup
// (~150 ns on llvmpipe, a few times its fragment work), so the splat pass costs what the number
// of points does. The particles are binned into cubes two spacings wide; a cube whose own and
// 26 neighbours' counts are nearly full is interior: every ray that reaches it passes through
// a neighbour first, whose particles give the visible depth. Its particles are replaced by
// one thickness splat at their centroid, twice as wide, carrying their summed volume (the
// thickness image is smooth, and its integral is unchanged). The 24k-particle dam break's
// starting block goes from 24,000 points to about 11,000.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace rtsph::render {

class SplatBatch {
 public:
  /// Rebuilds from positions (n each; z may be null in 2D, then nothing is merged) for a
  /// fluid of the given spacing (m). Reuses its buffers.
  void build(const float* x, const float* y, const float* z, std::size_t n, float spacing);
  /// Splats, SoA: x, y, z and weight (1: one particle, drawn with depth; k > 1: a merged cube
  /// of k particles, thickness only). size() entries each, in data() one array after another.
  std::size_t size() const { return size_; }
  std::size_t merged_cubes() const { return merged_; }
  const std::vector<float>& data() const { return out_; }

  /// Particles in a cube of two spacings when the lattice fills it; a cube counts as full from
  /// kFull of them (a free surface or a splash thins the count).
  static constexpr int kFull = 6;

 private:
  std::size_t size_ = 0, merged_ = 0;
  std::vector<float> out_;
  std::vector<std::int32_t> cell_of_;   // per particle
  std::vector<std::uint16_t> count_;    // per cube
  std::vector<std::uint8_t> full_, tmp_;
  std::vector<float> sum_;              // per cube: x, y, z sums of a merged cube
  std::vector<std::int32_t> slot_;      // per cube: its merged splat's index, −1 if none
};

}  // namespace rtsph::render
