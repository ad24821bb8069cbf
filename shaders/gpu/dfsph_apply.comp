// DFSPH's pressure kick (the CPU's Dfsph::apply_pressure): v_i += dt a_i with
//   a_i = -sum_j m (P_i + P_j) grad W_ij - 2 P_i sum_b Psi_b grad W_ib     (walls mirror P_i)
// P_i = kappa_i/rho_i from solve[i].x (a sweep's change) or solve[i].z (the warm start's total).
// Positions do not move during the solves, so the walk is the factors pass's. Returns at once
// when the solve's gate is closed (dfsph_gate.comp).
BUFFER_POS BUFFER_VEL BUFFER_FKEY BUFFER_FSTART BUFFER_WGRAD BUFFER_DFSPH_SOLVE BUFFER_STATS
uniform int source;  // the component of solve[] that holds P: 0 (x) or 2 (z)
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= P.fluid_count || stats[RTSPH_STAT_GATE].x == 0.0lf) return;
  vec3 xi = pos[i].xyz;
  uint key = fkey[i];
  float Pi = solve[i][source];
  vec3 a = vec3(0.0);
  for (int r = 0; r < stencil_count(); ++r) {
    uvec2 c = stencil_range(key, r);
    for (uint j = fstart[c.x]; j < fstart[c.y]; ++j) {
      vec3 d = min_image(xi - pos[j].xyz);
      float r2 = dot(d, d);
      if (r2 >= P.support2) continue;
      a += (-P.mass * (Pi + solve[j][source]) * kernel_g(r2)) * d;
    }
  }
  a -= (2.0 * Pi) * wgrad[i].xyz;
#if DIM == 2
  a.z = 0.0;
#endif
  vel[i].xyz += a * P.dt;
}
