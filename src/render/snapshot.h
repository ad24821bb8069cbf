#pragma once
// An owned copy of the particle arrays, so a renderer can draw while the solver runs on
// another thread (the solver reorders its arrays every step; views die at the next step).
#include <cstdint>
#include <vector>

#include "core/particles.h"

namespace rtsph::render {

struct ParticleSnapshot {
  int dim = 3;
  std::vector<float> x[3], v[3], density, pressure;
  std::vector<float> bx[3];
  std::vector<int32_t> owner;

  /// Copies the fluid (and the boundary when `boundary` is non-null). O(N) memcpy.
  void copy_from(const ParticleView& fluid, const BoundaryView* boundary);
  ParticleView fluid() const;
  BoundaryView boundary() const;
  std::size_t size() const { return x[0].size(); }
};

}  // namespace rtsph::render
