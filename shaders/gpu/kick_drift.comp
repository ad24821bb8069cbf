// The leapfrog's first half kick and its drift, fused (the CPU's kick, drift, put_back_escaped):
//   v += a dt/2;  x += v dt against the container's wall planes: a particle whose path crosses a
//   plane stops on it and loses the velocity component into the wall. Then the safety net: a
//   non-finite position is put back a quarter spacing inside and counted (a diagnostic).
BUFFER_POS BUFFER_VEL BUFFER_ACC
layout(std430, binding = RTSPH_B_REDUCE) buffer Counter { uint put_back; };
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= P.fluid_count) return;
  vec3 v = vel[i].xyz + acc[i].xyz * P.half_dt;
  vec3 x = pos[i].xyz;
  bool moved = false;
  for (int k = 0; k < DIM; ++k) {
    float lo = P.wall_lo[k], hi = P.wall_hi[k];
    float xn = x[k] + v[k] * P.dt, vk = v[k];
    bool below = xn < lo, above = xn > hi;
    x[k] = below ? lo : above ? hi : xn;
    v[k] = below ? max(vk, 0.0) : above ? min(vk, 0.0) : vk;
    // put_back_escaped: NaN fails both comparisons
    if (!(x[k] >= lo)) { x[k] = lo + P.put_back_margin; v[k] = max(v[k], 0.0); moved = true; }
    else if (!(x[k] <= hi)) { x[k] = hi - P.put_back_margin; v[k] = min(v[k], 0.0); moved = true; }
    if (isnan(v[k]) || isinf(v[k])) v[k] = 0.0;
  }
  if (moved) atomicAdd(put_back, 1u);
  pos[i] = vec4(x, 0.0);
  vel[i] = vec4(v, 0.0);
}
