// PBF, Algorithm 1 lines 9-10, one Jacobi iteration's first half (Macklin & Mueller 2013):
//   rho_i = sum_j m W_ij + sum_b Psi_b W_ib,  C_i = rho_i/rho0 - 1 (one-sided when clamped)   (eqs. 1-2)
//   lambda_i = -omega C_i / (sum_k |grad_k C_i|^2 + eps)                                        (eq. 11)
// with the CPU's weights: walls mirror lambda_i, so sum_k |grad_k C_i|^2 =
// ((grad_i C_i with walls doubled).grad_i C_i + sum_j |grad_j C_i|^2). The walls' gradient
// sum_b Psi_b grad W_ib is kept for the correction pass.
BUFFER_POS BUFFER_DENS BUFFER_FKEY BUFFER_FSTART BUFFER_BPOS BUFFER_BSTART BUFFER_LAMBDA BUFFER_WGRAD
uniform float eps, omega_relax;
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= P.fluid_count) return;
  vec3 xi = pos[i].xyz;
  uint key = fkey[i];
  float wf = 0.0, wb = 0.0, sq = 0.0;
  vec3 gf = vec3(0.0), gb = vec3(0.0);
  for (int r = 0; r < stencil_count(); ++r) {
    uvec2 c = stencil_range(key, r);
    for (uint j = fstart[c.x]; j < fstart[c.y]; ++j) {
      vec3 d = min_image(xi - pos[j].xyz);
      float r2 = dot(d, d);
      if (r2 >= P.support2) continue;
      float G = kernel_g(r2);
      wf += kernel_w(r2);
      sq += G * G * r2;
      gf += G * d;
    }
    for (uint j = bstart[c.x]; j < bstart[c.y]; ++j) {
      vec4 b = bpos[j];
      vec3 d = min_image(xi - b.xyz);
      float r2 = dot(d, d);
      if (r2 >= P.support2) continue;
      wb += b.w * kernel_w(r2);
      gb += (b.w * kernel_g(r2)) * d;
    }
  }
  float rho = P.mass * wf + wb;
  vec3 f = P.mass * gf;
  float grad2 = (dot(f + 2.0 * gb, f + gb) + P.mass * P.mass * sq) * (P.inv_rho0 * P.inv_rho0);
  float C = rho * P.inv_rho0 - 1.0;
  if ((P.flags & RTSPH_F_CLAMP_NEGATIVE) != 0u) C = max(C, 0.0);
  float l = -omega_relax * C / (grad2 + eps);
  dens[i].x = rho;
  lam[i] = vec2(l, lam[i].y + l);
  wgrad[i] = vec4(gb, 0.0);
}
