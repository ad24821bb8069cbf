// Reorders up to four vec4 arrays (COUNT) and optionally one uint array (GATHER_UINT) by the
// sort's permutation: out[i] = in[order[i]].
layout(std430, binding = RTSPH_B_VALS_IN) readonly buffer O { uint order[]; };
layout(std430, binding = RTSPH_B_GATHER_IN0) readonly buffer I0 { vec4 in0[]; };
layout(std430, binding = RTSPH_B_GATHER_OUT0) writeonly buffer O0 { vec4 out0[]; };
#if COUNT > 1
layout(std430, binding = RTSPH_B_GATHER_IN1) readonly buffer I1 { vec4 in1[]; };
layout(std430, binding = RTSPH_B_GATHER_OUT1) writeonly buffer O1 { vec4 out1[]; };
#endif
#if COUNT > 2
layout(std430, binding = RTSPH_B_GATHER_IN2) readonly buffer I2 { vec4 in2[]; };
layout(std430, binding = RTSPH_B_GATHER_OUT2) writeonly buffer O2 { vec4 out2[]; };
#endif
#if COUNT > 3 && !defined(GATHER_UINT)
layout(std430, binding = RTSPH_B_GATHER_IN3) readonly buffer I3 { vec4 in3[]; };
layout(std430, binding = RTSPH_B_GATHER_OUT3) writeonly buffer O3 { vec4 out3[]; };
#endif
#ifdef GATHER_UINT
layout(std430, binding = RTSPH_B_GATHER_IN3) readonly buffer U3 { uint uin[]; };
layout(std430, binding = RTSPH_B_GATHER_OUT3) writeonly buffer V3 { uint uout[]; };
#endif
uniform uint n;
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= n) return;
  uint j = order[i];
  out0[i] = in0[j];
#if COUNT > 1
  out1[i] = in1[j];
#endif
#if COUNT > 2
  out2[i] = in2[j];
#endif
#if COUNT > 3 && !defined(GATHER_UINT)
  out3[i] = in3[j];
#endif
#ifdef GATHER_UINT
  uout[i] = uin[j];
#endif
}
