// The particle sums every method shares: density, boundary volumes and pressure, and the
// acceleration sum (pressure, viscosity, external forces). Each fluid particle gathers from its
// neighbours in a fixed order (cell ranges, then 8-lane batches, then a fixed lane reduction),
// so results are bitwise identical for any thread count.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/pair_loop.h"
#include "solvers/fluid_world.h"

namespace rtsph {

using simd::f8;
using simd::i8;

namespace {
// The extrapolation factor β = 1 + d_b/dᵢ grows without bound as a particle nears the wall plane;
// Morris et al. 1997 cap it at 1.5, which leaves the flow of a resting lattice (first layer at
// dᵢ = s/2 from the plane, first samples at d_b = s/2 behind it: β = 2) slipping: measured
// +3.3% on Poiseuille's peak velocity at L/20. Instead a particle nearer than a quarter spacing
// counts as a quarter spacing away, which bounds β by 1 + 4·d_b/s and leaves the lattice's
// values exact (measured within 0.3% at L/20).
constexpr float kMinWallDistance = 0.25f;  // spacings
}  // namespace

template <int D>
const Real* FluidWorld<D>::pack_positions() {
  const std::size_t n = fluid_.size();
  if (!lists_current() || n == 0) return nullptr;
  constexpr std::size_t kStride = D == 3 ? 4 : 2;  // at_packed3's 16-byte records, at_packed2's 8
  ctx_.packed_x.resize(kStride * n);
  Real* out = ctx_.packed_x.data();
  pool_.parallel_for(n, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i)
      for (int k = 0; k < D; ++k) out[kStride * i + k] = fluid_.x[k][i];
  });
  return out;
}

// ρᵢ = Σⱼ m Wᵢⱼ + Σ_b Ψ_b W_ib. Without lists or periodic axes each fluid pair is visited once
// (half_stencil()): W is symmetric, so a pair adds its weight to both particles, and ρᵢ, which its
// partners add to as well, starts at zero. The same sum either way, in another order.
template <int D>
void FluidWorld<D>::compute_density() {
  const std::size_t n = fluid_.size();
  const Real mass = Real(prm_.mass), support2 = Real(prm_.support * prm_.support);
  const PairArrays<D> pa = pair_arrays();
  [[maybe_unused]] const auto &fx = pa.fx, &fv = pa.fv, &bx = pa.bx, &bv = pa.bv;
  [[maybe_unused]] const Real* const psi = pa.psi;
  const uint32_t* const cells = pa.cells;
  Real* rho = fluid_.rho.data();
  const bool half = half_stencil();
  if (half) clear(&rho, n, 1);
  const Real* const packed = pack_positions();
  with_kernel<D>(spec_.kernel, prm_.h, ctx_.fluid_grid.any_periodic(), [&](const auto& K) {
    auto particle = [&](std::size_t i, auto forward) {
      Real xi[D];
      for (int k = 0; k < D; ++k) xi[k] = fx[k][i];
      f8 wf{}, wb{};
      Real fluid = 0;  // the pairs' share of Σⱼ Wᵢⱼ (the forward walk adds the self term itself)
      if constexpr (decltype(forward)::value) {
        for_each_forward_batch<D>(ctx_.fluid_grid, cells[i], uint32_t(i), fx, xi, support2,
                                  [&](uint32_t j, const f8*, f8 r2, i8 m, int valid) {
                                    const f8 w = simd::select(m, K.value(r2), f8{});
                                    wf += w;
                                    add_forward(rho, j, mass * w, valid);
                                  });
        fluid = K.value(Real(0)) + simd::hsum(wf);
      } else {
        this->template for_each_fluid_batch<periodic_v<decltype(K)>>(i, fx, xi, support2,
                                    [&](auto, const f8*, f8 r2, i8 m) {
                                      wf += simd::select(m, K.value(r2), f8{});
                                    }, packed);
        fluid = simd::hsum(wf);
      }
      for_each_candidate_batch<D, periodic_v<decltype(K)>>(ctx_.boundary_grid, cells[i], bx, xi, support2,
                                  [&](auto j, const f8*, f8 r2, i8 m) {
                                    wb += simd::select(m, simd::at(psi, j) * K.value(r2), f8{});
                                  });
      const Real r = mass * fluid + simd::hsum(wb);
      if constexpr (decltype(forward)::value)
        rho[i] += r;
      else
        rho[i] = r;
    };
    for_each_pair_sum_particle<periodic_v<decltype(K)>>(half, n, particle);
  });
}

template <int D>
void FluidWorld<D>::clear(Real* const* arrays, std::size_t n, int count) {
  pool_.parallel_for(n, [&](std::size_t b, std::size_t e) {
    for (int k = 0; k < count; ++k) std::fill(arrays[k] + b, arrays[k] + e, Real(0));
  });
}

// aᵢ = −Σⱼ mⱼ (pᵢ/ρᵢ² + pⱼ/ρⱼ² + Πᵢⱼ) ∇Wᵢⱼ                      symmetric pressure (Monaghan 1992)
//      + Σⱼ mⱼ ν (1/ρᵢ + 1/ρⱼ) (rᵢⱼ·∇Wᵢⱼ)/(r² + η²) vᵢⱼ       laminar viscosity (Morris et al. 1997)
//      − Σ_b Ψ_b (pᵢ/ρᵢ² + p_b/ρ0² + Πᵢ_b) ∇Wᵢ_b + viscosity      boundary particles of Akinci
//        et al. 2012 with the wall pressure p_b of Adami et al. 2012, so the fluid next to a
//        wall carries the hydrostatic pressure instead of twice it (Akinci's p_b = 0 form)
//      + g + brush
// with vᵢⱼ = vᵢ − vⱼ (so viscosity pulls vᵢ towards vⱼ) and Monaghan's artificial viscosity
// Πᵢⱼ = −α c0 h (vᵢⱼ·rᵢⱼ) / (ρ̄ᵢⱼ (r² + η²)) for approaching pairs only (η² = 0.01 s², the
// spacing's, not h's: resolve_parameters); at a wall sample
// with a free-slip ghost's velocity, vᵢ − v_ghost = 2((vᵢ − v_b)·n)n (n the wall's normal).
//
// Each term is a template flag, so a method asking for a subset (DFSPH: viscosity and external
// forces, then pressure alone in its solver loops) pays only for what it uses.
template <int D>
void FluidWorld<D>::accelerations(const ForceTerms& t) {
  if (fluid_.size() == 0) return;
  const bool p = t.pressure != nullptr;
  if (p && t.viscosity && t.external) accelerations_impl<true, true, true>(t);
  else if (p && !t.viscosity && !t.external) accelerations_impl<true, false, false>(t);
  else if (!p && t.viscosity && t.external) accelerations_impl<false, true, true>(t);
  else if (!p && !t.viscosity && t.external) accelerations_impl<false, false, true>(t);
  else throw std::logic_error("accelerations: unsupported combination of force terms");
  // Surface tension and adhesion are non-pressure forces: they come with the external ones.
  if (t.external && t.surface && surface_forces_active()) add_surface_forces();
}

template <int D>
template <bool kPressure, bool kViscosity, bool kExternal>
void FluidWorld<D>::accelerations_impl(const ForceTerms& terms) {
  const std::size_t n = fluid_.size();
  const Real mass = Real(prm_.mass), support2 = Real(prm_.support * prm_.support);
  const Real eps = Real(prm_.eta2);
  const Real ach = Real(spec_.artificial_viscosity * prm_.c0 * prm_.h);
  const Real nu = Real(spec_.viscosity);
  const Real dmin = Real(kMinWallDistance * spec_.spacing);
  const PairArrays<D> pa = pair_arrays();
  [[maybe_unused]] const auto &fx = pa.fx, &fv = pa.fv, &bx = pa.bx, &bv = pa.bv;
  [[maybe_unused]] const Real* const psi = pa.psi;
  const Real* Pb = terms.boundary_pressure;
  const bool mirror = terms.mirror_boundary;
  const Real* rho = fluid_.rho.data();
  const Real* P = terms.pressure;
  const Real* inv_rho = ctx_.inv_rho.data();
  Real g[D];
  const Vec3d accel = external_acceleration();
  for (int k = 0; k < D; ++k) g[k] = Real(accel[k]);
  const bool hydro = terms.wall_hydrostatic;
  const Real inv_rho0 = Real(1.0 / prm_.rho0);
  const Brush brush = brush_;
  const Vec<D> brush_c = truncate<D>(brush.center);
  const Real* const packed = (kPressure || kViscosity) ? pack_positions() : nullptr;

  // Without lists or periodic axes each fluid pair is visited once, from the lower index, and
  // its term is added to both particles (equal masses, antisymmetric in d): aᵢ is then a sum
  // that its partners add to as well, so it starts at zero (half_stencil()).
  const bool half = (kPressure || kViscosity) && half_stencil();
  Real* a_out[D];
  for (int k = 0; k < D; ++k) a_out[k] = fluid_.a[k].data();
  if (half) clear(a_out, n);

  with_kernel<D>(spec_.kernel, prm_.h, ctx_.fluid_grid.any_periodic(), [&](const auto& K) {
    auto particle = [&](std::size_t i, auto forward) {
        Real xi[D], vi[D];
        for (int k = 0; k < D; ++k) { xi[k] = fx[k][i]; vi[k] = fv[k][i]; }
        const Real rhoi = rho[i], Pi = kPressure ? P[i] : Real(0), iri = kViscosity ? inv_rho[i] : Real(0);
        const Real Pbm = mirror ? Pi : Real(0);
        f8 acc[D] = {};
        if constexpr (kPressure || kViscosity) {
        // The pair's acceleration of i, c (masked lanes 0); j's is −c.
        auto pair = [&](auto j, const f8* d, f8 r2, i8 m, f8* c) {
              const f8 G = K.grad_factor(r2);  // ∇W = G · d
              f8 vij[D], vr = f8{};
              for (int k = 0; k < D; ++k) {
                vij[k] = vi[k] - simd::at(fv[k], j);
                vr += vij[k] * d[k];
              }
              f8 pij = f8{}, lam = f8{};
              if constexpr (kPressure) pij = Pi + simd::at(P, j);
              if constexpr (kViscosity) {
                const f8 rhoj = simd::at(rho, j);
                const f8 inv = simd::rcp(r2 + eps);
                pij += simd::select(vr < 0.0f, -ach * vr * inv * 2.0f * simd::rcp(rhoi + rhoj), f8{});
                lam = simd::select(m, mass * nu * (iri + simd::at(inv_rho, j)) * G * r2 * inv, f8{});
              }
              const f8 s = simd::select(m, -mass * pij * G, f8{});
              for (int k = 0; k < D; ++k) c[k] = kViscosity ? s * d[k] + lam * vij[k] : s * d[k];
        };
        this->template sum_antisymmetric_pairs<periodic_v<decltype(K)>>(i, forward, fx, xi, support2, packed, a_out, acc, pair);
        }
        // Boundary neighbours mirror the fluid particle's pressure and density (ρ_b = ρᵢ). The
        // cell comes from the position, not from the last sort: PBF calls this before it sorts,
        // after its corrections moved the particles (the same cell whenever memory is sorted).
        if (kPressure || kViscosity || hydro) {
        Vec<D> pos;
        for (int k = 0; k < D; ++k) pos[k] = xi[k];
        for_each_candidate_batch<D, periodic_v<decltype(K)>>(
            ctx_.boundary_grid, ctx_.boundary_grid.cell_of(pos), bx, xi, support2, [&](auto j, const f8* d, f8 r2, i8 m) {
              const f8 G = K.grad_factor(r2);
              f8 vib[D];
              for (int k = 0; k < D; ++k) vib[k] = vi[k] - simd::at(bv[k], j);
              const f8 w = simd::at(psi, j);
              f8 pib = f8{}, lam = f8{};
              if constexpr (kPressure) pib = Pi + (Pb ? simd::at(Pb, j) : f8{} + Pbm);
              if constexpr (kViscosity) {
                const f8 inv = simd::rcp(r2 + eps);
                // dn = n·(xᵢ − x_b): how far in front of the sample's face the particle is.
                f8 vn = f8{}, dn = f8{};
                for (int k = 0; k < D; ++k) {
                  const f8 nk = simd::at(pa.wall_normal[k], j);
                  vn += vib[k] * nk;
                  dn += nk * d[k];
                }
                // The artificial viscosity sees the sample as a free-slip ghost: the particle's
                // mirror image across the wall plane, which shares its tangential velocity and
                // reverses its normal one, so vᵢ − v_ghost = 2((vᵢ − v_b)·n)n. It damps the
                // approach to a wall and lets water slide along it. With the sample at rest in
                // its place instead (vᵢ − v_b whole), a film sliding down a wall was braked by
                // α c0 h, ~1e-3 m²/s at a 2 cm spacing, 1000 times water's ν: the 2D dam
                // break's column drained late at the back wall (docs/validation.md). Wall
                // friction is the laminar term's below, with water's own ν.
                const f8 vr = 2.0f * vn * dn;
                pib += simd::select(vr < 0.0f, -ach * vr * inv * iri, f8{});
                // No slip on the wall plane, not on the sample: the sample's velocity is
                // extrapolated through the wall, vᵢ − v_b → β(vᵢ − v_b), β = 1 + d_b/dᵢ
                // (d: distances to the plane; Morris, Fox & Zhu 1997, eqs. 30-31, with the
                // floor on dᵢ above). Without it the flow slips half a spacing into the wall.
                // Only for a particle in front of the sample (n·(xᵢ − x_b) > 0): behind it, the
                // sample's face is not the one facing the particle (the far face of a thin
                // obstacle), and the floor would turn β into 1 + d_b/dmin.
                const f8 depth = simd::at(pa.wall_depth, j);
                const f8 di = dn - depth;
                const f8 beta = simd::select((depth > 0.0f) & (dn > 0.0f),
                                             1.0f + depth * simd::rcp(simd::select(di > dmin, di, f8{} + dmin)),
                                             f8{} + 1.0f);
                lam = simd::select(m, beta * w * nu * (2.0f * iri) * G * r2 * inv, f8{});
              }
              if constexpr (kExternal) {
                if (hydro) {  // −Ψ_b (g·(x_b − xᵢ)/ρ0) ∇W_ib, with x_b − xᵢ = −d
                  f8 gd = f8{};
                  for (int k = 0; k < D; ++k) gd += g[k] * d[k];
                  pib -= gd * inv_rho0;
                }
              }
              const f8 s = simd::select(m, -w * pib * G, f8{});
              for (int k = 0; k < D; ++k) acc[k] += kViscosity ? s * d[k] + lam * vib[k] : s * d[k];
            });
        }
        Real ai[D];
        for (int k = 0; k < D; ++k) ai[k] = simd::hsum(acc[k]) + (kExternal ? g[k] : Real(0));
        if (kExternal && brush.active) {
          Vec<D> r;
          for (int k = 0; k < D; ++k) r[k] = xi[k] - brush_c[k];
          const Real dist = norm(r);
          if (dist < brush.radius && dist > 0) {
            const Real f = Real(brush.strength * (1.0 - dist / brush.radius)) / dist;
            for (int k = 0; k < D; ++k) ai[k] += f * r[k];
          }
        }
        for (int k = 0; k < D; ++k) {
          if constexpr (decltype(forward)::value)
            a_out[k][i] += ai[k];
          else
            a_out[k][i] = ai[k];
        }
    };
    for_each_pair_sum_particle<periodic_v<decltype(K)>>(half, n, particle);
  });
}

// p_b = (Σ_f p_f W_bf + (g − a_b)·Σ_f ρ_f (x_b − x_f) W_bf) / Σ_f W_bf   (Adami et al. 2012)
// a_b (the wall's acceleration) is neglected: obstacles move at prescribed, slowly varying speed.
template <int D>
void FluidWorld<D>::extrapolate_boundary_pressure() {
  const std::size_t n = boundary_.size();
  ctx_.boundary_p_over_rho2.resize(n);
  const Real support2 = Real(prm_.support * prm_.support);
  const Real inv_rho02 = Real(1.0 / (prm_.rho0 * prm_.rho0));
  const bool clamp = spec_.clamp_negative_pressure;
  const Real* fx[D];
  const Real* bx[D];
  for (int k = 0; k < D; ++k) { fx[k] = fluid_.x[k].data(); bx[k] = boundary_.x[k].data(); }
  const Real* p = fluid_.p.data();
  const Real* rho = fluid_.rho.data();
  const uint32_t* cells = ctx_.boundary_grid.sorted_cells();
  Real g[D];
  const Vec3d accel = external_acceleration();
  for (int k = 0; k < D; ++k) g[k] = Real(accel[k]);
  Real* out = ctx_.boundary_p_over_rho2.data();
  with_kernel<D>(spec_.kernel, prm_.h, ctx_.fluid_grid.any_periodic(), [&](const auto& K) {
    pool_.parallel_for(n, [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i) {
        Real xb[D];
        for (int k = 0; k < D; ++k) xb[k] = bx[k][i];
        f8 sw{}, sp{}, sg{};
        for_each_candidate_batch<D, periodic_v<decltype(K)>>(ctx_.fluid_grid, cells[i], fx, xb, support2,
                                    [&](auto j, const f8* d, f8 r2, i8 m) {
                                      const f8 w = simd::select(m, K.value(r2), f8{});
                                      f8 gd = f8{};
                                      for (int k = 0; k < D; ++k) gd += g[k] * d[k];
                                      sw += w;
                                      sp += w * simd::at(p, j);
                                      sg += w * simd::at(rho, j) * gd;
                                    });
        const Real wsum = simd::hsum(sw);
        Real pb = wsum > 0 ? (simd::hsum(sp) + simd::hsum(sg)) / wsum : Real(0);
        if (clamp && pb < 0) pb = 0;
        out[i] = pb * inv_rho02;
      }
    }, ThreadPool::kPairs);
  });
}

namespace {
// Σ W over one row of a square lattice of spacing s (a line in 2D, a plane in 3D) at distance
// `normal` from the particle, out to `reach` spacings on either side: the flat-wall calibrations'
// building block (lateral offsets on the first D − 1 axes, the normal on the last).
template <int D, class Kernel>
double lateral_sum(const Kernel& K, double s, int reach, double normal) {
  double sum = 0;
  for (int a = -reach; a <= reach; ++a)
    for (int c = (D == 3 ? -reach : 0); c <= (D == 3 ? reach : 0); ++c) {
      const double r2 = (double(a) * a + double(c) * c) * s * s + normal * normal;
      sum += double(K.value(Real(r2)));
    }
  return sum;
}

// Akinci's volume V_b = 1/Σ_k W_bk over-counts a wall sampled at the fluid spacing: next to a
// flat single-layer wall a fluid particle reaches 1.07 ρ0 in 2D at rest (and more in corners),
// and Tait's γ = 7 turns that into a burst at t = 0. We keep Akinci's per-particle volume (so
// sparse, dense and curved sampling still weigh right relative to each other) and scale it by
// the one factor that makes a fluid lattice resting on a flat wall sit exactly at ρ0.
template <int D, class Kernel>
double flat_wall_calibration(const Kernel& K, double s, int layers, double support) {
  const int reach = int(std::ceil(support / s)) + 1;
  auto lateral = [&](double normal) { return lateral_sum<D>(K, s, reach, normal); };
  double full = 0, half = 0;  // fluid lattice sums: all rows, and rows on the fluid side
  for (int n = -reach; n <= reach; ++n) {
    const double row = lateral(n * s);
    full += row;
    if (n >= 0) half += row;
  }
  // Boundary layers at normal distance (1 + l)·s below the fluid particle; Akinci sum of
  // layer l over all layers.
  double boundary = 0;
  for (int l = 0; l < layers; ++l) {
    double akinci = 0;
    for (int q = 0; q < layers; ++q) akinci += lateral((q - l) * s);
    boundary += lateral((1 + l) * s) / akinci;  // ρ0 V_l Σ W, in units of ρ0
  }
  return (1.0 - half / full) / boundary;
}

// A container wall of lattice samples, each with the fluid particle's own volume: the factor on
// m that makes a fluid lattice resting on the flat wall sit at ρ0. Its layers stand for the
// missing rows of the fluid's lattice, so it is 1 once they fill the support.
template <int D, class Kernel>
double lattice_wall_calibration(const Kernel& K, double s, int layers, double support) {
  const int reach = int(std::ceil(support / s)) + 1;
  auto lateral = [&](double normal) { return lateral_sum<D>(K, s, reach, normal); };
  double missing = 0, boundary = 0;  // the fluid rows beyond the wall plane; the wall's layers
  for (int n = 1; n <= reach; ++n) missing += lateral(n * s);
  for (int l = 0; l < layers; ++l) boundary += lateral((1 + l) * s);
  return boundary > 0 ? missing / boundary : 1.0;
}
}  // namespace

// Obstacles: Ψ_b = γ ρ0 / Σ_k W_bk over the boundary particles of the same body (Akinci et al.
// 2012, eq. 4-5), with γ from flat_wall_calibration; their shells are single, and curved ones
// irregular, which Akinci's volume weighs. Container walls: the lattice volume below. Rigid
// motion keeps Ψ constant.
template <int D>
void FluidWorld<D>::compute_boundary_psi() {
  const std::size_t n = boundary_.size();
  const Real support2 = Real(prm_.support * prm_.support);
  const Real* bx[D];
  for (int k = 0; k < D; ++k) bx[k] = boundary_.x[k].data();
  const int32_t* owner = boundary_.owner.data();
  with_kernel<D>(spec_.kernel, prm_.h, ctx_.fluid_grid.any_periodic(), [&](const auto& K) {
    const double gamma = flat_wall_calibration<D>(K, spec_.spacing, std::max(1, spec_.boundary_layers),
                                                  prm_.support);
    const double scale = gamma * prm_.rho0;
    // Container walls are the fluid's lattice continued (sample_walls): each sample stands for
    // one lattice cell, so it carries the fluid particle's mass (scaled to the wall lattice's
    // cell, which divides the domain), times the factor for the rows beyond its last layer.
    // Akinci's 1/Σ_k W_bk shrinks where samples crowd, at the box's edges and corners: measured
    // at rest in a 3D box (spacing 0.025 m), the fluid in a corner stood at 0.986 ρ0 with the
    // default single layer and 0.895 ρ0 with Wendland C2 at h = 2s and four layers, where this
    // volume gives ρ0 at every face, edge and corner (docs/validation.md, "Boundary volumes").
    const int layers = std::max(1, spec_.boundary_layers);
    double lattice_mass = prm_.mass * lattice_wall_calibration<D>(K, spec_.spacing, layers, prm_.support);
    for (int k = 0; k < D; ++k) {
      const double extent = spec_.domain_max[k] - spec_.domain_min[k];
      const double step = extent / double(std::max(1L, std::lround(extent / spec_.spacing)));
      lattice_mass *= step / spec_.spacing;
    }
    pool_.parallel_for(n, [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i) {
        if (owner[i] < 0) {
          boundary_.psi[i] = Real(lattice_mass);
          continue;
        }
        Vec<D> xi = boundary_.pos(i);
        const uint32_t cell = ctx_.boundary_grid.sorted_cells()[i];
        double sum = 0;
        ctx_.boundary_grid.for_each_range(cell, [&](uint32_t lo, uint32_t hi) {
          for (uint32_t j = lo; j < hi; ++j) {
            if (owner[j] != owner[i]) continue;
            Real d[D];
            for (int k = 0; k < D; ++k) d[k] = xi[k] - bx[k][j];
            ctx_.boundary_grid.wrap_offsets(d);
            Real r2 = 0;
            for (int k = 0; k < D; ++k) r2 += d[k] * d[k];
            if (r2 < support2) sum += K.value(r2);
          }
        });
        boundary_.psi[i] = Real(scale / sum);
      }
    }, ThreadPool::kPairs);
  });
}

#define RTSPH_INSTANTIATE(D)                          \
  template void FluidWorld<D>::compute_density();          \
  template const Real* FluidWorld<D>::pack_positions();     \
  template void FluidWorld<D>::accelerations(const ForceTerms&); \
  template void FluidWorld<D>::extrapolate_boundary_pressure(); \
  template void FluidWorld<D>::compute_boundary_psi();     \
  template void FluidWorld<D>::clear(Real* const*, std::size_t, int);
RTSPH_INSTANTIATE(2)
RTSPH_INSTANTIATE(3)
#undef RTSPH_INSTANTIATE

}  // namespace rtsph
