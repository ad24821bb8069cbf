// Exclusive prefix sum, second half: adds each block's scanned total to its values.
layout(std430, binding = RTSPH_B_SCAN) buffer S { uint data[]; };
layout(std430, binding = RTSPH_B_SCAN_SUMS) readonly buffer T { uint sums[]; };
uniform uint n;
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i < n) data[i] += sums[gl_WorkGroupID.x];
}
