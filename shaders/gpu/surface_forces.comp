// Surface tension and adhesion, pass 2 (FluidWorld::add_surface_forces; Akinci, Akinci &
// Teschner 2013, eqs. 1, 4, 6, 7), added to the acceleration the force pass wrote:
//   a_i += -gamma sum_j K_ij [ m C(r) x_ij/r + (n_i - n_j) ] - beta sum_b Psi_b A(r) x_ib/r
//   K_ij = 2 rho0/(rho_i + rho_j); C the cohesion spline, A the adhesion kernel (support H).
// surface = (gamma, beta, C's constant, A's constant), surface_b = (H, H^6/64, 2 rho0).
BUFFER_POS BUFFER_ACC BUFFER_DENS BUFFER_FSTART BUFFER_BPOS BUFFER_BSTART BUFFER_NORMAL
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= P.fluid_count) return;
  float gamma = P.surface.x, beta = P.surface.y, c_norm = P.surface.z, a_norm = P.surface.w;
  float H = P.surface_b.x, c_inner = P.surface_b.y, two_rho0 = P.surface_b.z;
  vec3 xi = pos[i].xyz;
  vec3 ni = gamma > 0.0 ? nrm[i].xyz : vec3(0.0);
  float rhoi = dens[i].x;
  // The cell from the position (as the CPU's pass): PBF adds these forces before its sort.
  uint key = cell_key(xi);
  vec3 a = vec3(0.0);
  for (int r = 0; r < stencil_count(); ++r) {
    uvec2 c = stencil_range(key, r);
    if (gamma > 0.0) {
      for (uint j = fstart[c.x]; j < fstart[c.y]; ++j) {
        vec3 d = min_image(xi - pos[j].xyz);
        float r2 = dot(d, d);
        if (!(r2 > 0.0 && r2 < P.support2)) continue;
        float rr = sqrt(r2), q = H - rr;
        float c1 = q * q * q * r2 * rr;
        float C = c_norm * (rr + rr > H ? c1 : c1 + c1 - c_inner);
        float Kij = two_rho0 / (rhoi + dens[j].x);
        a += (-gamma * Kij * P.mass * C / rr) * d + (-gamma * Kij) * (ni - nrm[j].xyz);
      }
    }
    if (beta > 0.0) {
      for (uint j = bstart[c.x]; j < bstart[c.y]; ++j) {
        vec4 b = bpos[j];
        vec3 d = min_image(xi - b.xyz);
        float r2 = dot(d, d);
        if (r2 >= P.support2) continue;
        float rr = sqrt(r2);
        if (!(rr + rr > H)) continue;  // A is zero inside H/2
        float arg = -4.0 * r2 / H + 6.0 * rr - 2.0 * H;
        float A = a_norm * sqrt(sqrt(max(arg, 0.0)));
        a += (-beta * b.w * A / rr) * d;
      }
    }
  }
#if DIM == 2
  a.z = 0.0;
#endif
  acc[i] = vec4(acc[i].xyz + a, 0.0);
}
