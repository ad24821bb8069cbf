// PBF, Algorithm 1 line 2: the external acceleration, gravity + brush, and the walls'
// hydrostatic pressure (Adami et al. 2012's rho g.(x_b - x_i) part; the CPU's
// ForceTerms::wall_hydrostatic): a_i = g + brush - sum_b Psi_b (-g.(x_i - x_b)/rho0) grad W_ib.
// The cell comes from the position: this runs before the step's sort.
BUFFER_POS BUFFER_ACC BUFFER_BPOS BUFFER_BSTART
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= P.fluid_count) return;
  vec3 xi = pos[i].xyz, g = P.gravity.xyz;
  uint key = cell_key(xi);
  vec3 a = vec3(0.0);
  for (int r = 0; r < stencil_count(); ++r) {
    uvec2 c = stencil_range(key, r);
    for (uint j = bstart[c.x]; j < bstart[c.y]; ++j) {
      vec4 b = bpos[j];
      vec3 d = min_image(xi - b.xyz);
      float r2 = dot(d, d);
      if (r2 >= P.support2) continue;
      float pib = -dot(g, d) * P.inv_rho0;
      a += (-b.w * pib * kernel_g(r2)) * d;
    }
  }
  a += g;
  if ((P.flags & RTSPH_F_BRUSH) != 0u) {
    vec3 rb = xi - P.brush.xyz;
#if DIM == 2
    rb.z = 0.0;
#endif
    float dist = length(rb);
    if (dist < P.brush.w && dist > 0.0) a += (P.brush_strength * (1.0 - dist / P.brush.w) / dist) * rb;
  }
#if DIM == 2
  a.z = 0.0;
#endif
  acc[i] = vec4(a, 0.0);
}
