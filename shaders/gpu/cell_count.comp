// Particles per cell from the sorted keys; an exclusive scan then gives each cell's first
// particle (the CPU grid's start array).
layout(std430, binding = RTSPH_B_KEYS_IN) readonly buffer K { uint keys[]; };
layout(std430, binding = RTSPH_B_SCAN) buffer S { uint counts[]; };
uniform uint n;
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i < n) atomicAdd(counts[keys[i]], 1u);
}
