// PBF, Algorithm 1 lines 9-10, one Jacobi iteration's first half (Macklin & Mueller 2013):
//   rho_i = sum_j m W_ij + sum_b Psi_b W_ib,  C_i = rho_i/rho0 - 1 (one-sided when clamped)   (eqs. 1-2)
//   lambda_i = -omega C_i / (sum_k |grad_k C_i|^2 + eps)                                        (eq. 11)
// with the CPU's weights: walls mirror lambda_i, so sum_k |grad_k C_i|^2 =
// ((grad_i C_i with walls doubled).grad_i C_i + sum_j |grad_j C_i|^2). The walls' gradient
// sum_b Psi_b grad W_ib is kept for the correction pass (wgrad.xyz). The substep's first pass
// (with_share) also puts s_corr's share of the equivalent pressure in wgrad.w (the CPU's
// Pbf::compute_lambda says why): half the mean of s_ij = -k (W/W(dq))^n weighted by the pairs'
// virial x_ij.grad W_ij = r^2 G, the walls' samples (Psi_b/m) in the weights with no s_corr.
// The pairs come from the substep's lists (pbf_list.comp), or the grid for a particle they
// could not hold. Returns at once when the solve's gate is closed (pbf_gate.comp).
BUFFER_POS BUFFER_DENS BUFFER_FKEY BUFFER_FSTART BUFFER_BPOS BUFFER_BSTART BUFFER_LAMBDA BUFFER_WGRAD
BUFFER_NLIST BUFFER_BLIST BUFFER_NCOUNT BUFFER_STATS
uniform float eps, omega_relax, inv_w_dq, k_corr, q_floor;
uniform int n_corr, with_share, use_lists;
uniform uint list_stride, fluid_cap, boundary_cap;

struct Sums {
  float wf, wb, sq, vw, vs;
  vec3 gf, gb;
};

void add_fluid(inout Sums s, vec3 xi, uint j) {
  vec3 d = min_image(xi - pos[j].xyz);
  float r2 = dot(d, d);
  if (r2 >= P.support2) return;
  float G = kernel_g(r2), w = kernel_w(r2);
  s.wf += w;
  s.sq += G * G * r2;
  s.gf += G * d;
  if (with_share != 0) {
    float q = w * inv_w_dq, qn = q;
    for (int p = 1; p < n_corr; ++p) qn *= q;
    qn = max(qn - q_floor, 0.0);
    s.vw += G * r2;
    s.vs += G * r2 * qn;
  }
}

void add_boundary(inout Sums s, vec3 xi, uint j) {
  vec4 b = bpos[j];
  vec3 d = min_image(xi - b.xyz);
  float r2 = dot(d, d);
  if (r2 >= P.support2) return;
  s.wb += b.w * kernel_w(r2);
  s.gb += (b.w * kernel_g(r2)) * d;
  if (with_share != 0) s.vw += (b.w / P.mass) * kernel_g(r2) * r2;
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= P.fluid_count || stats[RTSPH_STAT_GATE].x == 0.0lf) return;
  vec3 xi = pos[i].xyz;
  Sums s = Sums(0.0, 0.0, 0.0, 0.0, 0.0, vec3(0.0), vec3(0.0));
  uvec2 listed = use_lists != 0 ? ncount[i] : uvec2(0xffffffffu);
  if (listed.x <= fluid_cap && listed.y <= boundary_cap) {
    for (uint k = 0u; k < listed.x; ++k) add_fluid(s, xi, nlist[k * list_stride + i]);
    for (uint k = 0u; k < listed.y; ++k) add_boundary(s, xi, blist[k * list_stride + i]);
  } else {
    uint key = fkey[i];
    for (int r = 0; r < stencil_count(); ++r) {
      uvec2 c = stencil_range(key, r);
      for (uint j = fstart[c.x]; j < fstart[c.y]; ++j) add_fluid(s, xi, j);
      for (uint j = bstart[c.x]; j < bstart[c.y]; ++j) add_boundary(s, xi, j);
    }
  }
  float rho = P.mass * s.wf + s.wb;
  vec3 f = P.mass * s.gf;
  float grad2 = (dot(f + 2.0 * s.gb, f + s.gb) + P.mass * P.mass * s.sq) * (P.inv_rho0 * P.inv_rho0);
  float C = rho * P.inv_rho0 - 1.0;
  if ((P.flags & RTSPH_F_CLAMP_NEGATIVE) != 0u) C = max(C, 0.0);
  float l = -omega_relax * C / (grad2 + eps);
  dens[i].x = rho;
  float share = with_share == 0 ? wgrad[i].w : s.vw != 0.0 ? -0.5 * k_corr * s.vs / s.vw : 0.0;
  lam[i] = vec2(l, lam[i].y + l);
  wgrad[i] = vec4(s.gb, share);
}
