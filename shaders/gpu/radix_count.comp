// Radix sort, pass 1 of 2 per digit: how many keys of each block have each digit value. The
// counts are laid out digit-major (digit * blocks + block), so one exclusive scan gives every
// block's first slot for every digit. Atomics only count: the totals do not depend on order.
layout(std430, binding = RTSPH_B_KEYS_IN) readonly buffer K { uint keys[]; };
layout(std430, binding = RTSPH_B_COUNTS) writeonly buffer C { uint counts[]; };
uniform uint n, shift, blocks;
shared uint hist[RTSPH_RADIX];
void main() {
  uint t = gl_LocalInvocationID.x, i = gl_GlobalInvocationID.x;
  hist[t] = 0u;
  barrier();
  if (i < n) atomicAdd(hist[(keys[i] >> shift) & uint(RTSPH_RADIX - 1)], 1u);
  barrier();
  counts[t * blocks + gl_WorkGroupID.x] = hist[t];
}
