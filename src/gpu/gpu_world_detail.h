// What gpu_world.cpp and gpu_world_readback.cpp share: the stats buffer's slots and the
// dispatch size. Internal to the GPU backend.
#pragma once

#include <cstddef>

#include "gpu/gl_compute.h"
#include "gpu/layout.h"

namespace rtsph::gpu::detail {

// Slots of the stats buffer (reduce.comp writes them).
enum StatSlot : GLuint {
  kExtremes = 0, kDensity = 1, kEnergy = 2, kRanges = 3, kRanges2 = 4, kSolve = RTSPH_STAT_SOLVE, kHead = 6, kResidual = RTSPH_STAT_RESIDUAL,
  kGate = RTSPH_STAT_GATE, kSlots = 9
};
struct alignas(32) DVec4 { double x, y, z, w; };

inline GLuint blocks_of(std::size_t n) { return GLuint((n + RTSPH_WG - 1) / RTSPH_WG); }

}  // namespace rtsph::gpu::detail
