// Counting sort into cells, pass 1 of 3 (sort.cpp): each particle's cell key (in double, as the
// CPU's grid), and its cell's count. The atomic also hands out a provisional rank in the cell,
// in whatever order the threads ran: cell_sort_order.comp replaces it by a counted one.
layout(std430, binding = RTSPH_B_GATHER_IN0) readonly buffer In { vec4 xin[]; };
layout(std430, binding = RTSPH_B_KEYS_IN) writeonly buffer K { uint keys[]; };
layout(std430, binding = RTSPH_B_VALS_IN) writeonly buffer R { uint provisional[]; };
layout(std430, binding = RTSPH_B_SCAN) buffer S { uint counts[]; };
uniform uint n;
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= n) return;
  uint key = cell_key(xin[i].xyz);
  keys[i] = key;
  provisional[i] = atomicAdd(counts[key], 1u);
}
