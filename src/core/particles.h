#pragma once
// Structure-of-arrays particle storage. Fluid particles carry their state; boundary particles
// (Akinci et al. 2012) carry position, velocity (for moving obstacles) and the pseudo-mass
// Ψ = ρ0·V_b. All arrays are permuted together when particles are sorted by cell.
#include <array>
#include <cstdint>

#include "core/aligned_array.h"
#include "core/parallel.h"
#include "core/vec.h"

namespace rtsph {

template <int D>
struct FluidParticles {
  std::array<AlignedArray<Real>, D> x, v, a;  // m, m/s, m/s²
  AlignedArray<Real> rho, p;                  // kg/m³, Pa
  AlignedArray<uint32_t> id;                  // stable identity across reorders

  std::size_t size() const { return id.size(); }
  void resize(std::size_t n);
  void reserve(std::size_t n);
  Vec<D> pos(std::size_t i) const { Vec<D> r; for (int k = 0; k < D; ++k) r[k] = x[k][i]; return r; }
  Vec<D> vel(std::size_t i) const { Vec<D> r; for (int k = 0; k < D; ++k) r[k] = v[k][i]; return r; }
  void set_pos(std::size_t i, const Vec<D>& p_) { for (int k = 0; k < D; ++k) x[k][i] = p_[k]; }
  void set_vel(std::size_t i, const Vec<D>& v_) { for (int k = 0; k < D; ++k) v[k][i] = v_[k]; }
  std::size_t bytes() const;
  /// Reorders x, v and id so that new[i] = old[order[i]], in one parallel pass into `spare`
  /// whose buffers are then swapped in. a, ρ and p are left in the old order: callers sort
  /// right before recomputing them, so permuting them would be wasted bandwidth.
  struct Spare {
    std::array<AlignedArray<Real>, 2 * D> xv;
    AlignedArray<uint32_t> id;
    std::size_t bytes() const;
  };
  void permute_kinematics(const uint32_t* order, Spare& spare, const ThreadPool& pool);
};

template <int D>
struct BoundaryParticles {
  std::array<AlignedArray<Real>, D> x, v;  // m, m/s
  AlignedArray<Real> psi;                  // kg: ρ0 / Σ_k W_bk (Akinci 2012 eq. 4-5)
  AlignedArray<int32_t> owner;             // -1: container wall, else obstacle index
  AlignedArray<Real> local[D];             // position in the owner's body frame (m)

  std::size_t size() const { return owner.size(); }
  void resize(std::size_t n);
  Vec<D> pos(std::size_t i) const { Vec<D> r; for (int k = 0; k < D; ++k) r[k] = x[k][i]; return r; }
  std::size_t bytes() const;
  void permute(const uint32_t* order, AlignedArray<Real>& tmp, const ThreadPool& pool);
};

/// Read-only, dimension-erased view of the fluid for exporters and renderers. z is null in 2D.
struct ParticleView {
  int dim = 3;
  std::size_t count = 0;
  const float* x[3] = {};
  const float* v[3] = {};
  const float* density = nullptr;
  const float* pressure = nullptr;
  const uint32_t* id = nullptr;
};

/// Where a GPU backend keeps the fluid (OpenGL buffer names, one vec4 per particle), so a renderer
/// in the same context draws it without a copy: position xyz, velocity xyz, density (ρ, p, ·, ·).
/// The ranges are for the colour scale, reduced on the GPU.
struct DeviceParticles {
  unsigned position = 0, velocity = 0, density = 0;
  std::size_t count = 0;
  int dim = 3;
  float max_speed = 0, pressure_min = 0, pressure_max = 0, density_min = 0, density_max = 0;
};

struct BoundaryView {
  int dim = 3;
  std::size_t count = 0;
  const float* x[3] = {};
  const int32_t* owner = nullptr;  // -1 = container wall, else obstacle index
};

}  // namespace rtsph
