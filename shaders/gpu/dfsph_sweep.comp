// The applied change of a DFSPH sweep (the CPU's Dfsph::solve loop), Chebyshev-accelerated from
// the third sweep of a clamped density solve (Wang 2015): d = w delta + (w - 1) d_last, held so the
// total stays >= 0 when negative pressure is clamped; then total += d.
// Returns at once when the solve's gate is closed (dfsph_gate.comp).
BUFFER_DFSPH_SOLVE BUFFER_STATS
uniform float w, w1;
uniform int first;  // the solve's first sweep: no last change yet
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= P.fluid_count || stats[RTSPH_STAT_GATE].x == 0.0lf) return;
  vec4 s = solve[i];
  float d = w * s.x + (first != 0 ? 0.0 : w1 * s.y);
  if ((P.flags & RTSPH_F_CLAMP_NEGATIVE) != 0u && s.z + d < 0.0) d = -s.z;
  solve[i] = vec4(d, d, s.z + d, s.w);
}
