// Particle shifting, pass 2 (FluidWorld::displace_fluid): x += delta, wrapped along periodic
// axes and held inside the container's wall planes on the others. A shift is far below a cell,
// so the sort stays valid.
BUFFER_POS BUFFER_DELTA
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= P.fluid_count) return;
  vec3 x = pos[i].xyz + delta[i].xyz;
  for (int k = 0; k < DIM; ++k)
    if (P.period[k] > 0.0) x[k] = wrap_periodic(x[k], k);
  pos[i] = vec4(clamp_to_walls(x), 0.0);
}
