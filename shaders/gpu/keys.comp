// Cell key of every particle of the array bound at GATHER_IN0, and the identity permutation:
// the input of the stable radix sort (sort.cpp).
layout(std430, binding = RTSPH_B_GATHER_IN0) readonly buffer In { vec4 xin[]; };
layout(std430, binding = RTSPH_B_KEYS_IN) writeonly buffer K { uint keys_out[]; };
layout(std430, binding = RTSPH_B_VALS_IN) writeonly buffer V { uint vals_out[]; };
uniform uint n;
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= n) return;
  keys_out[i] = cell_key(xin[i].xyz);
  vals_out[i] = i;
}
