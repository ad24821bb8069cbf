// Radix sort, pass 2 of 2 per digit: each key goes to its block's first slot for its digit plus
// the number of keys before it in the block with the same digit. That rank is counted, not
// taken from an atomic, so the sort is stable and the result is the same on every run.
// The block is counted in slices of 32 keys: each slice's digit histogram (shared atomics, whose
// totals do not depend on order), then a key's rank is the same digit's count in the slices
// before its own plus the equal digits before it in its slice: at most 7 + 31 reads of shared
// memory per key instead of up to 255.
layout(std430, binding = RTSPH_B_KEYS_IN) readonly buffer KI { uint keys_in[]; };
layout(std430, binding = RTSPH_B_VALS_IN) readonly buffer VI { uint vals_in[]; };
layout(std430, binding = RTSPH_B_KEYS_OUT) writeonly buffer KO { uint keys_out[]; };
layout(std430, binding = RTSPH_B_VALS_OUT) writeonly buffer VO { uint vals_out[]; };
layout(std430, binding = RTSPH_B_COUNTS) readonly buffer C { uint offsets[]; };
uniform uint n, shift, blocks;
const uint kSlice = 32u;
const uint kSlices = uint(RTSPH_WG) / kSlice;
shared uint digit[RTSPH_WG];
shared uint slice_hist[kSlices * uint(RTSPH_RADIX)];  // [slice * RADIX + digit]
void main() {
  uint t = gl_LocalInvocationID.x, i = gl_GlobalInvocationID.x;
  uint key = i < n ? keys_in[i] : 0u;
  uint d = i < n ? (key >> shift) & uint(RTSPH_RADIX - 1) : uint(RTSPH_RADIX);
  digit[t] = d;
  for (uint k = t; k < kSlices * uint(RTSPH_RADIX); k += uint(RTSPH_WG)) slice_hist[k] = 0u;
  barrier();
  uint slice = t / kSlice;
  if (d < uint(RTSPH_RADIX)) atomicAdd(slice_hist[slice * uint(RTSPH_RADIX) + d], 1u);
  barrier();
  if (i >= n) return;
  uint rank = 0u;
  for (uint s = 0u; s < slice; ++s) rank += slice_hist[s * uint(RTSPH_RADIX) + d];
  for (uint s = slice * kSlice; s < t; ++s) rank += digit[s] == d ? 1u : 0u;
  uint slot = offsets[d * blocks + gl_WorkGroupID.x] + rank;
  keys_out[slot] = key;
  vals_out[slot] = vals_in[i];
}
