// DFSPH's residual and Jacobi sweep (the CPU's Dfsph::residual; Bender & Koschier 2017,
// Algorithms 2-3): with the current velocities
//   D rho_i/Dt = sum_j m (v_i - v_j).grad W_ij + 2 sum_b Psi_b (v_i - v_b).grad W_ib   (eq. 9)
// (a wall sample stands for a ghost that mirrors the particle's velocity relative to the wall,
// as its pressure: the CPU's src/solvers/dfsph_solve.cpp)
// and the residual r = rho_i + dt D rho_i/Dt - rho0 (density; minus the periodic bias; with
// solver.dfsph.surface_density "lattice" and clamped pressure, the target factor.w instead of rho0) or
// r = D rho_i/Dt (divergence), the sweep's pressure P = total + omega r alpha_i / dt^2 (or / dt),
// projected to P >= 0 when negative pressure is clamped; solve[i].x gets P - total. solve[i].w
// gets the particle's share of the mean relative error: |r| where pressure acts, compression
// elsewhere (clamped), |r| otherwise; zero for a thin neighbourhood in the divergence solve.
// With solver.dfsph.pressure_stabilisation beta > 0 the density residual also takes
// stab * sum_j |grad W_ij|^2 (P_i - P_j) off (stab = beta dt^2 m^2) and the sweep divides by 1 + beta
// (gain = omega / (1 + beta)): the CPU's pressure Laplacian, there with its reasons.
// Returns at once when the solve's gate is closed (dfsph_gate.comp).
BUFFER_POS BUFFER_VEL BUFFER_DENS BUFFER_FKEY BUFFER_FSTART BUFFER_WGRAD BUFFER_DFSPH_FACTOR BUFFER_DFSPH_SOLVE BUFFER_STATS
uniform int density;          // 1: the density solve, 0: the divergence solve
uniform double gain, to_p, bias, error_scale;  // omega/(1 + beta); 1/dt^2 or 1/dt; kg/m^3; 1/rho0 or dt/rho0
uniform double stab;          // beta dt^2 m^2 in the density solve, else 0
uniform float min_neighbours;
uniform int lattice;          // 1: the clamped density solve keeps factor.w (dfsph_factors.comp)
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= P.fluid_count || stats[RTSPH_STAT_GATE].x == 0.0lf) return;
  vec3 xi = pos[i].xyz, vi = vel[i].xyz;
  uint key = fkey[i];
  float Pi = solve[i].z;
  float rf = 0.0, lf = 0.0;
  for (int r = 0; r < stencil_count(); ++r) {
    uvec2 c = stencil_range(key, r);
    for (uint j = fstart[c.x]; j < fstart[c.y]; ++j) {
      vec3 d = min_image(xi - pos[j].xyz);
      float r2 = dot(d, d);
      if (r2 >= P.support2) continue;
      vec3 g = kernel_g(r2) * d;
      rf += dot(vi - vel[j].xyz, g);
      if (stab != 0.0lf) lf += (Pi - solve[j].z) * dot(g, g);
    }
  }
  vec4 fac = factor[i];
  double rate = double(P.mass) * double(rf) + 2.0lf * (double(dot(vi, wgrad[i].xyz)) - double(fac.z));
  bool clamp = (P.flags & RTSPH_F_CLAMP_NEGATIVE) != 0u;
  double target = lattice != 0 && clamp ? double(fac.w) : double(P.rho0);
  double r = density != 0 ? double(dens[i].x) + double(P.dt) * rate - target - bias - stab * double(lf) : rate;
  bool thin = density == 0 && fac.y < min_neighbours;
  vec4 s = solve[i];
  double p = thin ? 0.0lf : double(s.z) + gain * r * double(fac.x) * to_p;
  if (clamp) p = max(p, 0.0lf);
  if (thin) r = 0.0lf;
  else if (clamp) r = p > 0.0lf ? abs(r) : max(r, 0.0lf);
  else r = abs(r);
  // x and w only: neighbours read z (the total) in this pass.
  solve[i].x = float(p - double(s.z));
  solve[i].w = float(r * error_scale);
}
