// DFSPH's warm start and output (the CPU's Dfsph::solve and correct_divergence_error):
//   mode 0: the solve's total starts from a share of the last step's, stored independent of dt:
//           total = warm[component] * scale (scale = kWarm/dt^2 or kWarm/dt)
//   mode 1: warm[component] = total * scale (scale = dt^2 or dt)
//   mode 2: the step's pressure p = rho^2 (P_density + P_divergence) = rho^2 (warm.x/dt + warm.y)/dt
BUFFER_DENS BUFFER_DFSPH_SOLVE BUFFER_DFSPH_WARM
uniform int mode, component;
uniform double scale;
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= P.fluid_count) return;
  if (mode == 0) {
    solve[i].z = float(double(warm[i][component]) * scale);
  } else if (mode == 1) {
    warm[i][component] = float(double(solve[i].z) * scale);
  } else {
    double inv_dt = 1.0lf / double(P.dt), rho = double(dens[i].x);
    vec4 t = warm[i];
    dens[i].y = float((double(t.x) * inv_dt + double(t.y)) * inv_dt * rho * rho);
  }
}
