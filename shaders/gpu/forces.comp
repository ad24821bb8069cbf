// Accelerations, one fluid particle per thread (the CPU's FluidWorld::accelerations):
//   a_i = - sum_j m (P_i + P_j + Pi_ij) grad W_ij                     symmetric pressure (Monaghan 1992)
//         + sum_j m nu (1/rho_i + 1/rho_j) (r.grad W)/(r^2 + eta^2) v_ij     (Morris et al. 1997)
//         - sum_b Psi_b (P_i + P_b + Pi_ib) grad W_ib + beta-extrapolated wall viscosity
//         + g + brush
// with v_ij = v_i - v_j, Monaghan's Pi_ij = -alpha c0 h (v_ij.r_ij) / (rho_ij (r^2 + eta^2)) for
// approaching pairs (at a wall sample against a free-slip ghost: 2(v_ib.n)(n.r_ib)), and the
// no-slip factor beta = 1 + d_b/d_i on container walls and obstacle faces, for particles in front
// of the sample (Morris, Fox & Zhu 1997, eqs. 30-31; d_i floored at a quarter spacing).
// With NONPRESSURE (DFSPH's non-pressure accelerations, whose pressure comes from its solves):
// no P_i, P_j or Adami p_b; the walls carry the hydrostatic part alone, P_b = -g.(x_i - x_b)/rho0
// (the CPU's ForceTerms::wall_hydrostatic, as in pbf_external.comp).
BUFFER_POS BUFFER_VEL BUFFER_ACC BUFFER_DENS BUFFER_FKEY BUFFER_FSTART BUFFER_BPOS BUFFER_BVEL BUFFER_BNORMAL BUFFER_BSTART BUFFER_BPRESS
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= P.fluid_count) return;
  vec3 xi = pos[i].xyz, vi = vel[i].xyz;
  vec4 di = dens[i];
#ifdef NONPRESSURE
  float rhoi = di.x, Pi = 0.0, iri = di.w;
#else
  float rhoi = di.x, Pi = di.z, iri = di.w;
#endif
  uint key = fkey[i];
  vec3 a = vec3(0.0);
  for (int r = 0; r < stencil_count(); ++r) {
    uvec2 c = stencil_range(key, r);
    for (uint j = fstart[c.x]; j < fstart[c.y]; ++j) {
      vec3 d = min_image(xi - pos[j].xyz);
      float r2 = dot(d, d);
      if (r2 >= P.support2) continue;
      float G = kernel_g(r2);
      vec3 vij = vi - vel[j].xyz;
      float vr = dot(vij, d);
      vec4 dj = dens[j];
      float inv = 1.0 / (r2 + P.eps);
#ifdef NONPRESSURE
      float pij = 0.0;
#else
      float pij = Pi + dj.z;
#endif
      if (vr < 0.0) pij += -P.ach * vr * inv * 2.0 / (rhoi + dj.x);
      float lam = P.mass * P.nu * (iri + dj.w) * G * r2 * inv;
      a += (-P.mass * pij * G) * d + lam * vij;
    }
    for (uint j = bstart[c.x]; j < bstart[c.y]; ++j) {
      vec4 b = bpos[j];
      vec3 d = min_image(xi - b.xyz);
      float r2 = dot(d, d);
      if (r2 >= P.support2) continue;
      float G = kernel_g(r2);
      vec4 bv = bvel[j];
      vec3 vib = vi - bv.xyz;
      float inv = 1.0 / (r2 + P.eps);
#ifdef NONPRESSURE
      float pib = -dot(P.gravity.xyz, d) * P.inv_rho0;
#else
      float pib = Pi + bpress[j];
#endif
      float depth = bv.w;
      float front = dot(bnormal[j].xyz, d);  // > 0: x_i lies in front of the sample's face
      // Artificial viscosity against a free-slip ghost, v_i - v_ghost = 2((v_i - v_b).n)n, as the CPU.
      float vr = 2.0 * dot(vib, bnormal[j].xyz) * front;
      if (vr < 0.0) pib += -P.ach * vr * inv * iri;
      float dn = front - depth;
      float beta = depth > 0.0 && front > 0.0 ? 1.0 + depth / (dn > P.dmin ? dn : P.dmin) : 1.0;
      float lam = beta * b.w * P.nu * (2.0 * iri) * G * r2 * inv;
      a += (-b.w * pib * G) * d + lam * vib;
    }
  }
  a += P.gravity.xyz;
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
