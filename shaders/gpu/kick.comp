// v += a dt (the leapfrog's half kick; the host sets dt to half the step).
BUFFER_VEL BUFFER_ACC
uniform float dt;
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= P.fluid_count) return;
  vel[i] = vec4(vel[i].xyz + acc[i].xyz * dt, 0.0);
}
