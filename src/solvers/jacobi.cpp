// The stability of the density solves' Jacobi iterations, from the rest lattice. On a uniform
// lattice the iteration's operator (DFSPH: pressure → Δv → Dρ/Dt; PBF: λ → Δx → C, the same
// Σⱼ ∇Wᵢⱼ·(Δᵢ − Δⱼ) of a pairwise Σⱼ (λᵢ + λⱼ)∇Wᵢⱼ) is diagonal in Fourier modes
// λ_j = e^{iq·x_j}: it multiplies the mode by m²|S(q)|², S(q) = Σ_k sin(q·x_ik)∇W_ik, while the
// Jacobi diagonal is m²Σ_k|∇W_ik|² (Σ_k ∇W_ik = 0 there). An iteration therefore multiplies
// mode q by 1 − ω|S(q)|²/Σ|∇W|², and converges only for ω < 2/λmax, λmax = max_q |S(q)|²/Σ_k|∇W_ik|².
// The coherent sum grows with the neighbour count: λmax = 2.15 for the cubic spline at h = s in
// 2D (2.81 in 3D), 5.67 for Wendland C2 at h = 2s (44 neighbours). λmax from a scan of q over
// [0, π/s]^D.
#include "solvers/jacobi.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "core/kernels.h"

namespace rtsph {

template <int D>
double jacobi_lambda_max(const SimSpec& spec, const ResolvedParams& prm) {
  const double s = spec.spacing, support2 = prm.support * prm.support;
  const int reach = int(std::ceil(prm.support / s));
  std::vector<std::array<double, D>> offsets, grads;
  double diag = 0;
  with_kernel<D>(spec.kernel, prm.h, [&](const auto& K) {
    for (int z = (D == 3 ? -reach : 0); z <= (D == 3 ? reach : 0); ++z)
      for (int y = -reach; y <= reach; ++y)
        for (int x = -reach; x <= reach; ++x) {
          const int c[3] = {x, y, z};
          double r2 = 0;
          std::array<double, D> d{};
          for (int k = 0; k < D; ++k) { d[k] = c[k] * s; r2 += d[k] * d[k]; }
          if (r2 == 0 || r2 >= support2) continue;
          const double G = K.grad_factor(float(r2));
          std::array<double, D> g{};
          for (int k = 0; k < D; ++k) { g[k] = G * d[k]; diag += g[k] * g[k]; }
          offsets.push_back(d);
          grads.push_back(g);
        }
  });
  if (diag <= 0) return 0.0;
  const int nq = D == 2 ? 64 : 24;
  double lmax = 0;
  const int total = D == 2 ? nq * nq : nq * nq * nq;
  for (int idx = 0; idx < total; ++idx) {
    double q[D];
    int rest = idx;
    for (int k = 0; k < D; ++k) { q[k] = M_PI / s * (rest % nq) / (nq - 1); rest /= nq; }
    double S[D] = {};
    for (std::size_t j = 0; j < offsets.size(); ++j) {
      double phase = 0;
      for (int k = 0; k < D; ++k) phase += q[k] * offsets[j][k];
      const double sn = std::sin(phase);
      for (int k = 0; k < D; ++k) S[k] += sn * grads[j][k];
    }
    double s2 = 0;
    for (int k = 0; k < D; ++k) s2 += S[k] * S[k];
    lmax = std::max(lmax, s2 / diag);
  }
  return lmax;
}

template double jacobi_lambda_max<2>(const SimSpec&, const ResolvedParams&);
template double jacobi_lambda_max<3>(const SimSpec&, const ResolvedParams&);

}  // namespace rtsph
