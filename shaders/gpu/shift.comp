// Particle shifting, pass 1 (FluidWorld::shift_particles; Lind et al. 2012, the Fickian form with
// D = A h |v_i| dt of Skillen et al. 2013):
//   delta_i = -D grad C_i,  grad C_i = sum_j (m/rho_j) grad W_ij + sum_b (Psi_b/rho0) grad W_ib
// into delta; shift_apply.comp moves the particles once every one has gathered. Run right after
// the sort, with the densities the sort carried along (the last step's, as the CPU's). One fluid
// particle per thread.
BUFFER_POS BUFFER_VEL BUFFER_DENS BUFFER_FSTART BUFFER_BPOS BUFFER_BSTART BUFFER_DELTA
uniform float coeff;  // A h dt
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= P.fluid_count) return;
  vec3 xi = pos[i].xyz;
  uint key = cell_key(xi);
  vec3 g = vec3(0.0);
  for (int r = 0; r < stencil_count(); ++r) {
    uvec2 c = stencil_range(key, r);
    for (uint j = fstart[c.x]; j < fstart[c.y]; ++j) {
      vec3 d = min_image(xi - pos[j].xyz);
      float r2 = dot(d, d);
      if (r2 > 0.0 && r2 < P.support2) g += (P.mass * kernel_g(r2) / dens[j].x) * d;
    }
    for (uint j = bstart[c.x]; j < bstart[c.y]; ++j) {
      vec4 b = bpos[j];
      vec3 d = min_image(xi - b.xyz);
      float r2 = dot(d, d);
      if (r2 < P.support2) g += (b.w * P.inv_rho0 * kernel_g(r2)) * d;
    }
  }
  vec3 v = vel[i].xyz;
  float D = coeff * sqrt(dot(v, v));
  vec3 s = -D * g;
#if DIM == 2
  s.z = 0.0;
#endif
  delta[i] = vec4(s, 0.0);
}
