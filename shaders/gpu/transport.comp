// The transport-velocity formulation, pass 1 (FluidWorld::transport_velocity_shift; Adami, Hu &
// Adams 2013, eqs. 8 and 13): the push of a uniform background pressure p_b,
//   tdv_i = v~_i - v_i = -p_b dt_kick [ sum_j m (1/rho_i^2 + 1/rho_j^2) grad W_ij
//                                     + sum_b Psi_b (1/rho_i^2 + 1/rho0^2) grad W_ib ],
// at the positions and densities of the last force stage; kick_drift.comp (TRANSPORT) moves each
// particle by dt tdv before its drift, and transport_stress.comp adds the momentum correction
// after the next sort. One fluid particle per thread.
BUFFER_POS BUFFER_DENS BUFFER_FSTART BUFFER_BPOS BUFFER_BSTART BUFFER_TDV
uniform float coeff;  // p_b dt_kick
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= P.fluid_count) return;
  vec3 xi = pos[i].xyz;
  float rhoi = dens[i].x;
  float inv_rhoi2 = 1.0 / (rhoi * rhoi);
  float inv_rho02 = P.inv_rho0 * P.inv_rho0;
  uint key = cell_key(xi);
  vec3 g = vec3(0.0);
  for (int r = 0; r < stencil_count(); ++r) {
    uvec2 c = stencil_range(key, r);
    for (uint j = fstart[c.x]; j < fstart[c.y]; ++j) {
      vec3 d = min_image(xi - pos[j].xyz);
      float r2 = dot(d, d);
      if (!(r2 > 0.0 && r2 < P.support2)) continue;
      float rhoj = dens[j].x;
      g += (P.mass * (inv_rhoi2 + 1.0 / (rhoj * rhoj)) * kernel_g(r2)) * d;
    }
    for (uint j = bstart[c.x]; j < bstart[c.y]; ++j) {
      vec4 b = bpos[j];
      vec3 d = min_image(xi - b.xyz);
      float r2 = dot(d, d);
      if (r2 < P.support2) g += (b.w * (inv_rhoi2 + inv_rho02) * kernel_g(r2)) * d;
    }
  }
  vec3 dv = -coeff * g;
#if DIM == 2
  dv.z = 0.0;
#endif
  tdv[i] = vec4(dv, 0.0);
}
