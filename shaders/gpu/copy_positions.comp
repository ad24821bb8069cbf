// x* = x: PBF keeps the predicted positions (Algorithm 1, line 3) for the velocity update.
BUFFER_POS BUFFER_PRED
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= P.fluid_count) return;
  pred[i] = pos[i];
}
