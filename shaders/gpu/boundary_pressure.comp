// Wall pressure extrapolated from the fluid (Adami et al. 2012, eq. 27), per boundary sample:
//   p_b = (sum_f p_f W_bf + g . sum_f rho_f (x_b - x_f) W_bf) / sum_f W_bf
// stored as p_b / rho0^2, the form the symmetric pressure term uses.
BUFFER_POS BUFFER_DENS BUFFER_FSTART BUFFER_BPOS BUFFER_BKEY BUFFER_BPRESS
void main() {
  uint b = gl_GlobalInvocationID.x;
  if (b >= P.boundary_count) return;
  vec3 xb = bpos[b].xyz, g = P.gravity.xyz;
  uint key = bkey[b];
  float sw = 0.0, sp = 0.0, sg = 0.0;
  for (int r = 0; r < stencil_count(); ++r) {
    uvec2 c = stencil_range(key, r);
    for (uint j = fstart[c.x]; j < fstart[c.y]; ++j) {
      vec3 d = min_image(xb - pos[j].xyz);
      float r2 = dot(d, d);
      if (r2 >= P.support2) continue;
      float w = kernel_w(r2);
      vec4 dj = dens[j];
      sw += w;
      sp += w * dj.y;
      sg += w * dj.x * dot(g, d);
    }
  }
  float pb = sw > 0.0 ? (sp + sg) / sw : 0.0;
  if ((P.flags & RTSPH_F_CLAMP_NEGATIVE) != 0u && pb < 0.0) pb = 0.0;
  bpress[b] = pb * (P.inv_rho0 * P.inv_rho0);
}
