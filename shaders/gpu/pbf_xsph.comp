// PBF, Algorithm 1 line 22 (Macklin & Mueller 2013, section 5), first pass:
//   XSPH   dv_i = c sum_j (m/rho_j)(v_j - v_i) W_ij + c sum_b (Psi_b/rho0)(v_b - v_i) W_ib    (eq. 17)
//   omega_i = sum_j (m/rho_j) grad_i W_ij x (v_j - v_i)                                       (eq. 15)
// and the density the corrections reached, rho_i = sum_j m W_ij + sum_b Psi_b W_ib, into
// dens_next (the volumes here use the last lambda pass's density, as on the CPU). The pairs come
// from the substep's lists (pbf_list.comp), or the grid for a particle they could not hold.
BUFFER_POS BUFFER_VEL BUFFER_DENS BUFFER_FKEY BUFFER_FSTART BUFFER_BPOS BUFFER_BVEL BUFFER_BSTART
BUFFER_DENS_NEXT BUFFER_DELTA BUFFER_OMEGA BUFFER_NLIST BUFFER_BLIST BUFFER_NCOUNT
uniform float xsph_c;
uniform int vorticity, use_lists;
uniform uint list_stride, fluid_cap, boundary_cap;

struct Sums {
  float wf, wb;
  vec3 dv, dvb, om;
};

void add_fluid(inout Sums s, vec3 xi, vec3 vi, uint j) {
  vec3 d = min_image(xi - pos[j].xyz);
  float r2 = dot(d, d);
  if (r2 >= P.support2) return;
  float vol = P.mass / dens[j].x, W = kernel_w(r2);
  vec3 vji = vel[j].xyz - vi;
  s.wf += W;
  s.dv += (vol * W) * vji;
  if (vorticity != 0) s.om += (vol * kernel_g(r2)) * cross(d, vji);
}

void add_boundary(inout Sums s, vec3 xi, vec3 vi, uint j) {
  vec4 b = bpos[j];
  vec3 d = min_image(xi - b.xyz);
  float r2 = dot(d, d);
  if (r2 >= P.support2) return;
  float w = b.w * kernel_w(r2);
  s.wb += w;
  s.dvb += w * (bvel[j].xyz - vi);
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= P.fluid_count) return;
  vec3 xi = pos[i].xyz, vi = vel[i].xyz;
  Sums s = Sums(0.0, 0.0, vec3(0.0), vec3(0.0), vec3(0.0));
  uvec2 listed = use_lists != 0 ? ncount[i] : uvec2(0xffffffffu);
  if (listed.x <= fluid_cap && listed.y <= boundary_cap) {
    for (uint k = 0u; k < listed.x; ++k) add_fluid(s, xi, vi, nlist[k * list_stride + i]);
    for (uint k = 0u; k < listed.y; ++k) add_boundary(s, xi, vi, blist[k * list_stride + i]);
  } else {
    uint key = fkey[i];
    for (int r = 0; r < stencil_count(); ++r) {
      uvec2 c = stencil_range(key, r);
      for (uint j = fstart[c.x]; j < fstart[c.y]; ++j) add_fluid(s, xi, vi, j);
      for (uint j = bstart[c.x]; j < bstart[c.y]; ++j) add_boundary(s, xi, vi, j);
    }
  }
  dens_next[i] = vec4(P.mass * s.wf + s.wb, dens[i].y, 0.0, 0.0);
  vec3 change = xsph_c * (s.dv + P.inv_rho0 * s.dvb);
#if DIM == 2
  change.z = 0.0;
#endif
  delta[i] = vec4(change, 0.0);
  omega[i] = vec4(s.om, 0.0);
}
