// PBF, vorticity confinement (Macklin & Mueller 2013, eq. 16), second pass:
//   eta_i = sum_j (m/rho_j)(|omega_j| - |omega_i|) grad_i W_ij,  N = eta/|eta|,  dv_i += dt eps (N x omega_i)
// with the density the corrections reached (the XSPH pass's).
BUFFER_POS BUFFER_DENS BUFFER_FKEY BUFFER_FSTART BUFFER_DELTA BUFFER_OMEGA
uniform float step_eps;
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= P.fluid_count) return;
  vec3 xi = pos[i].xyz, wi = omega[i].xyz;
  float wabs = length(wi);
  uint key = fkey[i];
  vec3 eta = vec3(0.0);
  for (int r = 0; r < stencil_count(); ++r) {
    uvec2 c = stencil_range(key, r);
    for (uint j = fstart[c.x]; j < fstart[c.y]; ++j) {
      vec3 d = min_image(xi - pos[j].xyz);
      float r2 = dot(d, d);
      if (r2 >= P.support2) continue;
      eta += ((P.mass / dens[j].x) * (length(omega[j].xyz) - wabs) * kernel_g(r2)) * d;
    }
  }
#if DIM == 2
  eta.z = 0.0;
#endif
  float len2 = dot(eta, eta);
  if (len2 <= 1e-20) return;
  vec3 N = eta * inversesqrt(len2);
  vec3 change = step_eps * cross(N, wi);
#if DIM == 2
  change.z = 0.0;
#endif
  delta[i] += vec4(change, 0.0);
}
