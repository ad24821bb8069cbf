// Reductions over the fluid in a fixed order (a tree per workgroup, then one workgroup over the
// partials), in double, so every run gives the same bits. MODE selects what is reduced:
//   0: (max |v|^2, max |a|^2)                    the adaptive time step
//   1: (max e, sum e, non-finite count, -)       e = max(0, rho/rho0 - 1); the health check
//   2: (sum m|v|^2/2, sum -m g.x, max |v|^2, -)  energies and the maximum speed
//   3: (max |v|^2, max rho, max -rho, max p)     the colour scale's ranges (drawing)
//   4: (max -p, -, -, -)
//   5: (max z, max -z, -, -) with z = -g.x      DFSPH's head: the fluid's extent along gravity
//   6: (sum solve.w, -, -, -)                    DFSPH's mean residual error
//   7: (sum rho, -, -, -)                        DFSPH's density bias in a filled periodic box
// FINAL = 0: partials[1 + block] for each block; FINAL = 1: reduces those into stats[slot]
// (mode 1 also keeps the running maximum in stats[slot].w).
BUFFER_POS BUFFER_VEL BUFFER_ACC BUFFER_DENS
#if MODE == 6
BUFFER_DFSPH_SOLVE
#endif
layout(std430, binding = RTSPH_B_REDUCE) buffer R { dvec4 partials[]; };
layout(std430, binding = RTSPH_B_STATS) buffer S { dvec4 stats[]; };
uniform uint n, slot;
uniform vec3 g_energy;  // mode 2: gravity alone (the potential energy; not the body force)
uniform dvec3 g_head;   // mode 5: gravity alone, in double as the CPU's DFSPH step takes it
shared dvec4 tmp[RTSPH_WG];

#if MODE >= 3 && MODE <= 5
const dvec4 kIdentity = dvec4(-1e300lf);
#else
const dvec4 kIdentity = dvec4(0.0lf);
#endif

dvec4 combine(dvec4 a, dvec4 b) {
#if MODE == 0 || (MODE >= 3 && MODE <= 5)
  return max(a, b);
#elif MODE >= 6
  return dvec4(a.x + b.x, 0.0lf, 0.0lf, 0.0lf);
#elif MODE == 1
  return dvec4(max(a.x, b.x), a.y + b.y, a.z + b.z, 0.0lf);
#else
  return dvec4(a.x + b.x, a.y + b.y, max(a.z, b.z), 0.0lf);
#endif
}

bool bad(vec4 v) { return any(isnan(v)) || any(isinf(v)); }

dvec4 item(uint i) {
#if MODE == 0
  dvec3 v = dvec3(vel[i].xyz), a = dvec3(acc[i].xyz);
  return dvec4(v.x * v.x + v.y * v.y + v.z * v.z, a.x * a.x + a.y * a.y + a.z * a.z, 0.0lf, 0.0lf);
#elif MODE == 1
  vec4 d = dens[i];
  double e = max(0.0lf, double(d.x) * double(P.inv_rho0) - 1.0lf);
  double nonfinite = (bad(pos[i]) || bad(vel[i]) || bad(vec4(d.xy, 0.0, 0.0))) ? 1.0lf : 0.0lf;
  return dvec4(e, e, nonfinite, 0.0lf);
#elif MODE == 2
  dvec3 v = dvec3(vel[i].xyz), x = dvec3(pos[i].xyz), g = dvec3(g_energy);
  double v2 = v.x * v.x + v.y * v.y + v.z * v.z;
  return dvec4(0.5lf * double(P.mass) * v2, -double(P.mass) * (g.x * x.x + g.y * x.y + g.z * x.z), v2, 0.0lf);
#elif MODE == 3
  dvec3 v = dvec3(vel[i].xyz);
  vec4 d = dens[i];
  return dvec4(v.x * v.x + v.y * v.y + v.z * v.z, double(d.x), -double(d.x), double(d.y));
#elif MODE == 4
  return dvec4(-double(dens[i].y), -1e300lf, -1e300lf, -1e300lf);
#elif MODE == 5
  dvec3 x = dvec3(pos[i].xyz), g = g_head;
  double z = -(g.x * x.x + g.y * x.y + g.z * x.z);
  return dvec4(z, -z, -1e300lf, -1e300lf);
#elif MODE == 6
  return dvec4(double(solve[i].w), 0.0lf, 0.0lf, 0.0lf);
#else
  return dvec4(double(dens[i].x), 0.0lf, 0.0lf, 0.0lf);
#endif
}

void main() {
  uint t = gl_LocalInvocationID.x;
  dvec4 acc_ = kIdentity;
#if FINAL == 0
  uint i = gl_GlobalInvocationID.x;
  if (i < n) acc_ = item(i);
#else
  for (uint k = t; k < n; k += uint(RTSPH_WG)) acc_ = combine(acc_, partials[1u + k]);
#endif
  tmp[t] = acc_;
  barrier();
  for (uint s = uint(RTSPH_WG) / 2u; s > 0u; s >>= 1) {
    if (t < s) tmp[t] = combine(tmp[t], tmp[t + s]);
    barrier();
  }
  if (t != 0u) return;
#if FINAL == 0
  partials[1u + gl_WorkGroupID.x] = tmp[0];
#else
  dvec4 r = tmp[0];
#if MODE == 1
  r.w = max(stats[slot].w, r.x);
#endif
  stats[slot] = r;
#endif
}
