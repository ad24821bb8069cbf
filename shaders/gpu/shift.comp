// Particle shifting, pass 1 (FluidWorld::shift_particles; Lind et al. 2012, the Fickian form with
// D = A h |v_i| dt of Skillen et al. 2013):
//   delta_i = -D grad~C_i,  grad~C_i = sum_j (m/rho_j) f_ij grad W_ij + sum_b (Psi_b/rho0) f_ib grad W_ib
// with Lind's anti-clumping weight f = 1 + 0.2 (W/W(dp))^4; a surface particle (div r below 1.5 in
// 2D, 2.4 in 3D) keeps only the part along the surface, normal to the plain grad C_i; no shift
// exceeds 0.2 initial spacings.
// Into delta; shift_apply.comp moves the particles once every one has gathered. Run right after
// the sort, with the densities the sort carried along (the last step's, as the CPU's). One fluid
// particle per thread.
BUFFER_POS BUFFER_VEL BUFFER_DENS BUFFER_FSTART BUFFER_BPOS BUFFER_BSTART BUFFER_DELTA
uniform float coeff;     // A h dt
uniform float inv_w_dp;  // 1 / W(initial spacing)
uniform float most;      // the largest shift in one step (m)
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= P.fluid_count) return;
  vec3 xi = pos[i].xyz;
  uint key = cell_key(xi);
  vec3 g = vec3(0.0), gc = vec3(0.0);
  float div = 0.0;
  for (int r = 0; r < stencil_count(); ++r) {
    uvec2 c = stencil_range(key, r);
    for (uint j = fstart[c.x]; j < fstart[c.y]; ++j) {
      vec3 d = min_image(xi - pos[j].xyz);
      float r2 = dot(d, d);
      if (r2 > 0.0 && r2 < P.support2) {
        float s = P.mass * kernel_g(r2) / dens[j].x;
        float q = kernel_w(r2) * inv_w_dp, q2 = q * q;
        g += s * d;
        gc += (s * (1.0 + 0.2 * q2 * q2)) * d;
        div -= s * r2;
      }
    }
    for (uint j = bstart[c.x]; j < bstart[c.y]; ++j) {
      vec4 b = bpos[j];
      vec3 d = min_image(xi - b.xyz);
      float r2 = dot(d, d);
      if (r2 < P.support2) {
        float s = b.w * P.inv_rho0 * kernel_g(r2);
        float q = kernel_w(r2) * inv_w_dp, q2 = q * q;
        g += s * d;
        gc += (s * (1.0 + 0.2 * q2 * q2)) * d;
        div -= s * r2;
      }
    }
  }
  float norm2 = dot(g, g);
  if (div < (DIM == 2 ? 1.5 : 2.4) && norm2 > 0.0) gc -= (dot(gc, g) / norm2) * g;
  vec3 v = vel[i].xyz;
  float D = coeff * sqrt(dot(v, v));
  float len2 = dot(gc, gc);
  if (D * D * len2 > most * most) D = most / sqrt(len2);
  vec3 s = -D * gc;
#if DIM == 2
  s.z = 0.0;
#endif
  delta[i] = vec4(s, 0.0);
}
