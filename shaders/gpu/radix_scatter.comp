// Radix sort, pass 2 of 2 per digit: each key goes to its block's first slot for its digit plus
// the number of keys before it in the block with the same digit. That rank is counted, not
// taken from an atomic, so the sort is stable and the result is the same on every run.
layout(std430, binding = RTSPH_B_KEYS_IN) readonly buffer KI { uint keys_in[]; };
layout(std430, binding = RTSPH_B_VALS_IN) readonly buffer VI { uint vals_in[]; };
layout(std430, binding = RTSPH_B_KEYS_OUT) writeonly buffer KO { uint keys_out[]; };
layout(std430, binding = RTSPH_B_VALS_OUT) writeonly buffer VO { uint vals_out[]; };
layout(std430, binding = RTSPH_B_COUNTS) readonly buffer C { uint offsets[]; };
uniform uint n, shift, blocks;
shared uint digit[RTSPH_WG];
void main() {
  uint t = gl_LocalInvocationID.x, i = gl_GlobalInvocationID.x;
  uint key = i < n ? keys_in[i] : 0u;
  uint d = i < n ? (key >> shift) & uint(RTSPH_RADIX - 1) : uint(RTSPH_RADIX);
  digit[t] = d;
  barrier();
  if (i >= n) return;
  uint rank = 0u;
  for (uint s = 0u; s < t; ++s) rank += digit[s] == d ? 1u : 0u;
  uint slot = offsets[d * blocks + gl_WorkGroupID.x] + rank;
  keys_out[slot] = key;
  vals_out[slot] = vals_in[i];
}
