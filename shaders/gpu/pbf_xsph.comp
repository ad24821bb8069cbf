// PBF, Algorithm 1 line 22 (Macklin & Mueller 2013, section 5), first pass:
//   XSPH   dv_i = c sum_j (m/rho_j)(v_j - v_i) W_ij + c sum_b (Psi_b/rho0)(v_b - v_i) W_ib    (eq. 17)
//   omega_i = sum_j (m/rho_j) grad_i W_ij x (v_j - v_i)                                       (eq. 15)
// and the density the corrections reached, rho_i = sum_j m W_ij + sum_b Psi_b W_ib, into
// dens_next (the volumes here use the last lambda pass's density, as on the CPU).
BUFFER_POS BUFFER_VEL BUFFER_DENS BUFFER_FKEY BUFFER_FSTART BUFFER_BPOS BUFFER_BVEL BUFFER_BSTART
BUFFER_DENS_NEXT BUFFER_DELTA BUFFER_OMEGA
uniform float xsph_c;
uniform int vorticity;
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= P.fluid_count) return;
  vec3 xi = pos[i].xyz, vi = vel[i].xyz;
  uint key = fkey[i];
  float wf = 0.0, wb = 0.0;
  vec3 dv = vec3(0.0), dvb = vec3(0.0), om = vec3(0.0);
  for (int r = 0; r < stencil_count(); ++r) {
    uvec2 c = stencil_range(key, r);
    for (uint j = fstart[c.x]; j < fstart[c.y]; ++j) {
      vec3 d = min_image(xi - pos[j].xyz);
      float r2 = dot(d, d);
      if (r2 >= P.support2) continue;
      float vol = P.mass / dens[j].x, W = kernel_w(r2);
      vec3 vji = vel[j].xyz - vi;
      wf += W;
      dv += (vol * W) * vji;
      if (vorticity != 0) om += (vol * kernel_g(r2)) * cross(d, vji);
    }
    for (uint j = bstart[c.x]; j < bstart[c.y]; ++j) {
      vec4 b = bpos[j];
      vec3 d = min_image(xi - b.xyz);
      float r2 = dot(d, d);
      if (r2 >= P.support2) continue;
      float w = b.w * kernel_w(r2);
      wb += w;
      dvb += w * (bvel[j].xyz - vi);
    }
  }
  dens_next[i] = vec4(P.mass * wf + wb, dens[i].y, 0.0, 0.0);
  vec3 change = xsph_c * (dv + P.inv_rho0 * dvb);
#if DIM == 2
  change.z = 0.0;
#endif
  delta[i] = vec4(change, 0.0);
  omega[i] = vec4(om, 0.0);
}
