// PBF: v_i += dv_i, the XSPH and vorticity change, once every particle's was found.
BUFFER_VEL BUFFER_DELTA
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= P.fluid_count) return;
  vel[i] = vec4(vel[i].xyz + delta[i].xyz, 0.0);
}
