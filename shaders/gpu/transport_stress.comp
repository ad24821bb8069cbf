// The transport-velocity formulation, pass 2 (FluidWorld::add_transport_velocity_stress; Adami et
// al. 2013, eq. 8): the divergence of A = rho v (v~ - v), added to the force stage's acceleration:
//   a_i += sum_j m (1/rho_i^2 + 1/rho_j^2) 1/2 (A_i + A_j) . grad W_ij   (fluid pairs only: the
// walls' samples carry no A). One fluid particle per thread.
BUFFER_POS BUFFER_VEL BUFFER_ACC BUFFER_DENS BUFFER_FSTART BUFFER_TDV
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= P.fluid_count) return;
  vec3 xi = pos[i].xyz, vi = vel[i].xyz, dvi = tdv[i].xyz;
  float rhoi = dens[i].x;
  float inv_rhoi2 = 1.0 / (rhoi * rhoi);
  uint key = cell_key(xi);
  vec3 a = vec3(0.0);
  for (int r = 0; r < stencil_count(); ++r) {
    uvec2 c = stencil_range(key, r);
    for (uint j = fstart[c.x]; j < fstart[c.y]; ++j) {
      vec3 d = min_image(xi - pos[j].xyz);
      float r2 = dot(d, d);
      if (!(r2 > 0.0 && r2 < P.support2)) continue;
      float rhoj = dens[j].x;
      float cij = 0.5 * P.mass * (inv_rhoi2 + 1.0 / (rhoj * rhoj)) * kernel_g(r2);
      a += (cij * rhoi * dot(dvi, d)) * vi + (cij * rhoj * dot(tdv[j].xyz, d)) * vel[j].xyz;
    }
  }
#if DIM == 2
  a.z = 0.0;
#endif
  acc[i] = vec4(acc[i].xyz + a, 0.0);
}
