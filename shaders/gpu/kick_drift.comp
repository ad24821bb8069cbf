// A kick and a drift, fused (the CPU's kick, drift, put_back_escaped): WCSPH's first half kick
// (kick_dt = dt/2) or PBF's prediction (kick_dt = dt):
//   v += a kick_dt;  x += v dt against the container's wall planes: a particle whose path crosses a
//   plane stops on it and loses the velocity component into the wall; along a periodic axis it
//   wraps to the other end. Then the safety net: a
//   non-finite position is put back a quarter spacing inside and counted (a diagnostic).
BUFFER_POS BUFFER_VEL BUFFER_ACC
#ifdef TRANSPORT
BUFFER_TDV
#endif
layout(std430, binding = RTSPH_B_REDUCE) buffer Counter { uint put_back_count; };
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= P.fluid_count) return;
  vec3 v = vel[i].xyz + acc[i].xyz * P.kick_dt;
  vec3 x = pos[i].xyz;
#ifdef TRANSPORT
  // The transport velocity's displacement dt (v~ - v) first, wrapped and held inside the walls
  // as the CPU's displace_fluid does, then the drift.
  x += tdv[i].xyz * P.dt;
  for (int k = 0; k < DIM; ++k)
    if (P.period[k] > 0.0) x[k] = wrap_periodic(x[k], k);
  x = clamp_to_walls(x);
#endif
  for (int k = 0; k < DIM; ++k) {
    if (P.period[k] > 0.0) {  // no walls: wrap (FluidWorld::drift)
      x[k] = wrap_periodic(x[k] + v[k] * P.dt, k);
      continue;
    }
    float lo = P.wall_lo[k], hi = P.wall_hi[k];
    float xn = x[k] + v[k] * P.dt, vk = v[k];
    bool below = xn < lo, above = xn > hi;
    x[k] = below ? lo : above ? hi : xn;
    v[k] = below ? max(vk, 0.0) : above ? min(vk, 0.0) : vk;
  }
  if (put_back(x, v)) atomicAdd(put_back_count, 1u);  // NaN fails both wall comparisons
  pos[i] = vec4(x, 0.0);
  vel[i] = vec4(v, 0.0);
}
