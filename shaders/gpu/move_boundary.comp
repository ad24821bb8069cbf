// Rigid motion of obstacle samples: x = c + R x_local, v = v_c + omega x (x - c), and the wall
// normal n = R n_local of the sample's face (blocal.w, layout.h); its depth (bvel.w) is fixed.
BUFFER_BPOS BUFFER_BVEL BUFFER_BNORMAL BUFFER_BLOCAL BUFFER_OBSTACLES
void main() {
  uint b = gl_GlobalInvocationID.x;
  if (b >= P.boundary_count) return;
  int owner = int(bnormal[b].w);
  if (owner < 0) return;
  Obstacle o = obstacles[owner];
  vec3 l = blocal[b].xyz;
  vec3 x = o.center.xyz + vec3(dot(o.r0.xyz, l), dot(o.r1.xyz, l), dot(o.r2.xyz, l));
  vec3 v = o.velocity.xyz + cross(o.omega.xyz, x - o.center.xyz);
#if DIM == 2
  x.z = 0.0;
  v.z = 0.0;
#endif
  int face = int(blocal[b].w);
  vec3 nl = vec3(0.0);
  if (face == RTSPH_FACE_RADIAL) {
    float r = length(l);
    if (r > 0.0) nl = l / r;
  } else if (face != 0) {
    nl[abs(face) - 1] = face < 0 ? -1.0 : 1.0;
  }
  vec3 n = vec3(dot(o.r0.xyz, nl), dot(o.r1.xyz, nl), dot(o.r2.xyz, nl));
#if DIM == 2
  n.z = 0.0;
#endif
  bpos[b] = vec4(x, bpos[b].w);
  bvel[b] = vec4(v, bvel[b].w);
  bnormal[b] = vec4(n, bnormal[b].w);
}
