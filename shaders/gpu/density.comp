// Density and equation of state, one fluid particle per thread (WCSPH; with DENSITY_ONLY the
// density alone, for the other methods):
//   rho_i = sum_j m W_ij + sum_b Psi_b W_ib            (Akinci et al. 2012, eq. 6)
//   p_i = B((rho_i/rho0)^gamma - 1)  or  k(rho_i - rho0)  (Becker & Teschner 2007; linear)
// dens[i] = (rho, p, p/rho^2, 1/rho), the EOS in double as on the CPU (the Tait bracket cancels).
BUFFER_POS BUFFER_DENS BUFFER_FKEY BUFFER_FSTART BUFFER_BPOS BUFFER_BSTART
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= P.fluid_count) return;
  vec3 xi = pos[i].xyz;
  uint key = fkey[i];
  float wf = 0.0, wb = 0.0;
  for (int r = 0; r < stencil_count(); ++r) {
    uvec2 c = stencil_range(key, r);
    for (uint j = fstart[c.x]; j < fstart[c.y]; ++j) {
      vec3 d = min_image(xi - pos[j].xyz);
      float r2 = dot(d, d);
      if (r2 < P.support2) wf += kernel_w(r2);
    }
    for (uint j = bstart[c.x]; j < bstart[c.y]; ++j) {
      vec4 b = bpos[j];
      vec3 d = min_image(xi - b.xyz);
      float r2 = dot(d, d);
      if (r2 < P.support2) wb += b.w * kernel_w(r2);
    }
  }
  float rho = P.mass * wf + wb;
#ifdef DENSITY_ONLY
  dens[i].x = rho;  // FluidWorld::compute_density: the density alone
  return;
#endif
  double rd = double(rho), x = rd / double(P.rho0), p;
  if ((P.flags & RTSPH_F_LINEAR_EOS) != 0u) {
    p = double(P.stiffness) * (rd - double(P.rho0));
  } else {
    double xg = P.tait_gamma == 7.0 ? x * x * x * x * x * x * x : double(pow(float(x), P.tait_gamma));
    p = double(P.tait_b) * (xg - 1.0lf);
  }
  if ((P.flags & RTSPH_F_CLAMP_NEGATIVE) != 0u && p < 0.0lf) p = 0.0lf;
  dens[i] = vec4(rho, float(p), float(p / (rd * rd)), float(1.0lf / rd));
}
