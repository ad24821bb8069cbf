// Exclusive prefix sum, level pass: each workgroup scans its RTSPH_WG values in place and
// writes their total to sums[block] (scanned in turn, then added back by scan_add.comp).
layout(std430, binding = RTSPH_B_SCAN) buffer S { uint data[]; };
layout(std430, binding = RTSPH_B_SCAN_SUMS) writeonly buffer T { uint sums[]; };
uniform uint n;
shared uint tmp[RTSPH_WG];
void main() {
  uint t = gl_LocalInvocationID.x, i = gl_GlobalInvocationID.x;
  uint v = i < n ? data[i] : 0u;
  tmp[t] = v;
  barrier();
  for (uint off = 1u; off < uint(RTSPH_WG); off <<= 1) {  // Hillis-Steele inclusive scan
    uint add = t >= off ? tmp[t - off] : 0u;
    barrier();
    tmp[t] += add;
    barrier();
  }
  if (i < n) data[i] = tmp[t] - v;
  if (t == uint(RTSPH_WG - 1)) sums[gl_WorkGroupID.x] = tmp[t];
}
