// PBF, Algorithm 1 lines 13-14, the Jacobi iteration's second half:
//   dx_i = (1/rho0)[sum_j m (lambda_i + lambda_j + s_corr) grad W_ij + sum_b Psi_b 2 lambda_i grad W_ib]  (eq. 14)
//   s_corr = -k [(W(r)/W(dq))^n - (W(r*)/W(dq))^n]+, r* where |grad W| peaks (pbf::gradient_peak)     (eq. 13)
// then x_i + dx_i, stopped on a container wall plane (collision response), into pos_next: every
// correction of an iteration reads the same positions. The fluid pairs come from the substep's
// lists (pbf_list.comp), or the grid for a particle they could not hold. When the solve's gate
// is closed (pbf_gate.comp) it copies the positions along, since the host swaps the two
// position buffers after every correction it queued.
BUFFER_POS BUFFER_FKEY BUFFER_FSTART BUFFER_LAMBDA BUFFER_WGRAD BUFFER_POS_NEXT BUFFER_NLIST BUFFER_NCOUNT
BUFFER_STATS
uniform float inv_w_dq, k_corr, q_floor;
uniform int n_corr, use_lists;
uniform uint list_stride, fluid_cap;

vec3 pair(vec3 xi, float li, uint j) {
  vec3 d = min_image(xi - pos[j].xyz);
  float r2 = dot(d, d);
  if (r2 >= P.support2) return vec3(0.0);
  float q = kernel_w(r2) * inv_w_dq, qn = q;
  for (int p = 1; p < n_corr; ++p) qn *= q;
  qn = max(qn - q_floor, 0.0);  // only below the kernel's gradient peak (pbf::gradient_peak)
  return (li + lam[j].x - k_corr * qn) * kernel_g(r2) * d;
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= P.fluid_count) return;
  if (stats[RTSPH_STAT_GATE].x == 0.0lf) {
    pos_next[i] = pos[i];
    return;
  }
  vec3 xi = pos[i].xyz;
  float li = lam[i].x;
  vec3 a = vec3(0.0);
  uint listed = use_lists != 0 ? ncount[i].x : 0xffffffffu;
  if (listed <= fluid_cap) {
    for (uint k = 0u; k < listed; ++k) a += pair(xi, li, nlist[k * list_stride + i]);
  } else {
    uint key = fkey[i];
    for (int r = 0; r < stencil_count(); ++r) {
      uvec2 c = stencil_range(key, r);
      for (uint j = fstart[c.x]; j < fstart[c.y]; ++j) a += pair(xi, li, j);
    }
  }
  vec3 dx = (P.mass * P.inv_rho0) * a + (2.0 * li * P.inv_rho0) * wgrad[i].xyz;
#if DIM == 2
  dx.z = 0.0;
#endif
  pos_next[i] = vec4(clamp_to_walls(xi + dx), 0.0);
}
