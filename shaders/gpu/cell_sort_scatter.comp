// Counting sort into cells, pass 2 of 3: each particle to its cell's first slot (the scanned
// counts) plus its provisional rank, with its key.
layout(std430, binding = RTSPH_B_KEYS_IN) readonly buffer K { uint keys[]; };
layout(std430, binding = RTSPH_B_VALS_IN) readonly buffer R { uint provisional[]; };
layout(std430, binding = RTSPH_B_SCAN) readonly buffer S { uint start[]; };
layout(std430, binding = RTSPH_B_KEYS_OUT) writeonly buffer KO { uint keys_out[]; };
layout(std430, binding = RTSPH_B_VALS_OUT) writeonly buffer VO { uint unordered[]; };
uniform uint n;
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= n) return;
  uint key = keys[i];
  uint slot = start[key] + provisional[i];
  keys_out[slot] = key;
  unordered[slot] = i;
}
