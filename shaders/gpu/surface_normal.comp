// Surface tension, pass 1 (FluidWorld::add_surface_forces; Akinci, Akinci & Teschner 2013,
// eq. 5): the surface normal n_i = H sum_j (m/rho_j) grad W_ij over fluid neighbours (the self
// term has grad W = 0). One fluid particle per thread.
BUFFER_POS BUFFER_DENS BUFFER_FSTART BUFFER_NORMAL
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= P.fluid_count) return;
  vec3 xi = pos[i].xyz;
  uint key = cell_key(xi);
  vec3 a = vec3(0.0);
  for (int r = 0; r < stencil_count(); ++r) {
    uvec2 c = stencil_range(key, r);
    for (uint j = fstart[c.x]; j < fstart[c.y]; ++j) {
      vec3 d = min_image(xi - pos[j].xyz);
      float r2 = dot(d, d);
      if (r2 > 0.0 && r2 < P.support2) a += (kernel_g(r2) / dens[j].x) * d;
    }
  }
  nrm[i] = vec4(P.surface_b.x * P.mass * a, 0.0);
}
