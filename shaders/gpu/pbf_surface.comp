// PBF's surface forces at the predicted positions (the CPU's Pbf::surface_forces_at_prediction:
// with the constraint that balances them, so the step adds no torque). Two modes around
// surface_forces.comp:
//   mode 0: delta = a (line 2's f_ext, already applied, kept), a = 0, so that surface_forces.comp
//           then leaves the surface forces alone in a;
//   mode 1: v += dt a_s, x* += dt^2 a_s (held inside the walls), a = f_ext + a_s.
BUFFER_POS BUFFER_VEL BUFFER_ACC BUFFER_DELTA
uniform int mode;
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= P.fluid_count) return;
  vec3 a = acc[i].xyz;
  if (mode == 0) {
    delta[i] = vec4(a, 0.0);
    acc[i] = vec4(0.0);
    return;
  }
  vel[i] = vec4(vel[i].xyz + a * P.dt, 0.0);
  pos[i] = vec4(clamp_to_walls(pos[i].xyz + a * (P.dt * P.dt)), 0.0);
  acc[i] = vec4(delta[i].xyz + a, 0.0);
}
