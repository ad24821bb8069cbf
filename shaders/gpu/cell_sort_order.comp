// Counting sort into cells, pass 3 of 3: within each cell, the particles in the order of their
// previous index, so that the order does not depend on which thread's atomic came first, and
// equals the CPU's stable counting sort (core/grid.cpp). A particle's final rank is counted: how
// many in its cell had a smaller index. That is quadratic in the cell's count, a few dozen in
// any flow; a cell holding more than kMaxRanked (only a blow-up, NaNs all falling in one cell,
// can gather that many in a cell two smoothing lengths wide) keeps the provisional order.
layout(std430, binding = RTSPH_B_KEYS_OUT) readonly buffer K { uint keys[]; };
layout(std430, binding = RTSPH_B_VALS_OUT) readonly buffer U { uint unordered[]; };
layout(std430, binding = RTSPH_B_SCAN) readonly buffer S { uint start[]; };
layout(std430, binding = RTSPH_B_COUNTS) writeonly buffer O { uint order[]; };
uniform uint n;
const uint kMaxRanked = 4096u;
void main() {
  uint s = gl_GlobalInvocationID.x;
  if (s >= n) return;
  uint key = keys[s], first = start[key], end = start[key + 1u];
  uint v = unordered[s];
  if (end - first > kMaxRanked) {
    order[s] = v;
    return;
  }
  uint rank = 0u;
  for (uint t = first; t < end; ++t) rank += unordered[t] < v ? 1u : 0u;
  order[first + rank] = v;
}
