// Shared by every GPU compute pass (prepended after layout.h): the parameter block, the particle
// buffers, the smoothing kernels and the neighbour grid. DIM (2 or 3) and KERNEL are #defined
// by the host. ASCII only.

layout(std140, binding = RTSPH_U_PARAMS) uniform ParamsBlock { SphParams P; };

// Storage blocks are declared by the passes that use them (Mesa counts declared blocks against
// the 16 a compute shader may have): BUFFER_POS, BUFFER_VEL, ... each expand to one declaration.
#define BUFFER_POS layout(std430, binding = RTSPH_B_POS) buffer PosBuf { vec4 pos[]; };
#define BUFFER_VEL layout(std430, binding = RTSPH_B_VEL) buffer VelBuf { vec4 vel[]; };
#define BUFFER_ACC layout(std430, binding = RTSPH_B_ACC) buffer AccBuf { vec4 acc[]; };
#define BUFFER_DENS layout(std430, binding = RTSPH_B_DENS) buffer DensBuf { vec4 dens[]; };
#define BUFFER_ID layout(std430, binding = RTSPH_B_ID) buffer IdBuf { uint pid[]; };
#define BUFFER_FKEY layout(std430, binding = RTSPH_B_FKEY) buffer FKeyBuf { uint fkey[]; };
#define BUFFER_FSTART layout(std430, binding = RTSPH_B_FSTART) buffer FStartBuf { uint fstart[]; };
#define BUFFER_BPOS layout(std430, binding = RTSPH_B_BPOS) buffer BPosBuf { vec4 bpos[]; };
#define BUFFER_BVEL layout(std430, binding = RTSPH_B_BVEL) buffer BVelBuf { vec4 bvel[]; };
#define BUFFER_BNORMAL layout(std430, binding = RTSPH_B_BNORMAL) buffer BNormalBuf { vec4 bnormal[]; };
#define BUFFER_BLOCAL layout(std430, binding = RTSPH_B_BLOCAL) buffer BLocalBuf { vec4 blocal[]; };
#define BUFFER_BKEY layout(std430, binding = RTSPH_B_BKEY) buffer BKeyBuf { uint bkey[]; };
#define BUFFER_BSTART layout(std430, binding = RTSPH_B_BSTART) buffer BStartBuf { uint bstart[]; };
#define BUFFER_BPRESS layout(std430, binding = RTSPH_B_BPRESS) buffer BPressBuf { float bpress[]; };
#define BUFFER_PRED layout(std430, binding = RTSPH_B_PRED) buffer PredBuf { vec4 pred[]; };
#define BUFFER_LAMBDA layout(std430, binding = RTSPH_B_LAMBDA) buffer LambdaBuf { vec2 lam[]; };
#define BUFFER_WGRAD layout(std430, binding = RTSPH_B_WGRAD) buffer WGradBuf { vec4 wgrad[]; };
#define BUFFER_DENS_NEXT layout(std430, binding = RTSPH_B_DENS_NEXT) buffer DensNextBuf { vec4 dens_next[]; };
#define BUFFER_POS_NEXT layout(std430, binding = RTSPH_B_POS_NEXT) buffer PosNextBuf { vec4 pos_next[]; };
#define BUFFER_NLIST layout(std430, binding = RTSPH_B_NLIST) buffer NListBuf { uint nlist[]; };
#define BUFFER_BLIST layout(std430, binding = RTSPH_B_BLIST) buffer BListBuf { uint blist[]; };
#define BUFFER_NCOUNT layout(std430, binding = RTSPH_B_NCOUNT) buffer NCountBuf { uvec2 ncount[]; };
#define BUFFER_DELTA layout(std430, binding = RTSPH_B_DELTA) buffer DeltaBuf { vec4 delta[]; };
#define BUFFER_OMEGA layout(std430, binding = RTSPH_B_OMEGA) buffer OmegaBuf { vec4 omega[]; };
#define BUFFER_OBSTACLES layout(std430, binding = RTSPH_B_OBSTACLES) buffer ObstacleBuf { Obstacle obstacles[]; };
#define BUFFER_NORMAL layout(std430, binding = RTSPH_B_NORMAL) buffer NormalBuf { vec4 nrm[]; };
#define BUFFER_DFSPH_SOLVE layout(std430, binding = RTSPH_B_DFSPH_SOLVE) buffer DfsphSolveBuf { vec4 solve[]; };
#define BUFFER_DFSPH_FACTOR layout(std430, binding = RTSPH_B_DFSPH_FACTOR) buffer DfsphFactorBuf { vec4 factor[]; };
#define BUFFER_DFSPH_WARM layout(std430, binding = RTSPH_B_DFSPH_WARM) buffer DfsphWarmBuf { vec4 warm[]; };
#define BUFFER_STATS layout(std430, binding = RTSPH_B_STATS) buffer StatsBuf { dvec4 stats[]; };
#define BUFFER_TDV layout(std430, binding = RTSPH_B_TDV) buffer TdvBuf { vec4 tdv[]; };

// ---- Kernels: the CPU's formulas (core/kernels.h) with the constants its objects hold.
#if KERNEL == 0
// Cubic spline (Monaghan & Lattanzio 1985): kernel_a = (h, 1/h, sigma, gsigma), kernel_b.x = tiny.
float kernel_w(float r2) {
  float q = r2 * inversesqrt(r2 + P.kernel_b.x) * P.kernel_a.y;
  float a = max(2.0 - q, 0.0), b = max(1.0 - q, 0.0);
  return P.kernel_a.z * (0.25 * a * a * a - b * b * b);
}
float kernel_g(float r2) {  // grad W = kernel_g(r2) * (xi - xj)
  float inv_r = inversesqrt(r2 + P.kernel_b.x);
  float q = r2 * inv_r * P.kernel_a.y;
  float a = max(2.0 - q, 0.0), b = max(1.0 - q, 0.0);
  return (P.kernel_a.w * P.kernel_a.x) * (-0.75 * a * a + 3.0 * b * b) * inv_r;
}
#elif KERNEL == 1
// Wendland C2: kernel_a = (h, 1/h, sigma, gsigma), kernel_b.x = tiny.
float kernel_w(float r2) {
  float q = r2 * inversesqrt(r2 + P.kernel_b.x) * P.kernel_a.y;
  float a = max(1.0 - 0.5 * q, 0.0);
  return P.kernel_a.z * (a * a * a * a * (2.0 * q + 1.0));
}
float kernel_g(float r2) {
  float q = r2 * inversesqrt(r2 + P.kernel_b.x) * P.kernel_a.y;
  float a = max(1.0 - 0.5 * q, 0.0);
  return P.kernel_a.w * (-5.0 * a * a * a);
}
#elif KERNEL == 2
// Poly6 value, spiky gradient (Mueller et al. 2003): kernel_a = (R, R^2, 1/R, poly6), kernel_b.x = spiky.
float kernel_w(float r2) {
  float d = max(P.kernel_a.y - r2, 0.0);
  return P.kernel_a.w * d * d * d;
}
float kernel_g(float r2) {
  float r = sqrt(r2);
  float d = max(P.kernel_a.x - r, 0.0);
  return (-3.0 * P.kernel_b.x) * d * d / (r + 1e-12 * P.kernel_a.x);
}
#else
// Truncated Gaussian (Gingold & Monaghan 1977): kernel_a = (h, 1/h^2, sigma, cutoff^2).
float kernel_w(float r2) {
  return r2 < P.kernel_a.w ? P.kernel_a.z * exp(-r2 * P.kernel_a.y) : 0.0;
}
float kernel_g(float r2) { return (-2.0 * P.kernel_a.y) * kernel_w(r2); }
#endif

// ---- Neighbour grid: the CPU's UniformGrid (core/grid.cpp), keys with x fastest, cell indices
// in double so that both backends put a particle in the same cell.
uint cell_key(vec3 p) {
  uint key = 0u, stride = 1u;
  for (int a = 0; a < DIM; ++a) {
    double f = (double(p[a]) - P.grid_origin[a]) * P.grid_inv_cell[a];
    int dims = P.grid_dims[a];
    if (P.period[a] > 0.0) {  // wrap into the period's cells 1..n (an overshoot past the seam)
      double n = double(dims - 2);
      f = 1.0lf + (f - 1.0lf) - n * floor((f - 1.0lf) / n);
    }
    int c = f >= 1.0lf ? (f < double(dims - 1) ? int(f) : dims - 2) : 1;  // NaN -> cell 1
    key += uint(c) * stride;
    stride *= uint(dims);
  }
  return key;
}

// The minimum image of an offset x_i - x_j along the periodic axes (UniformGrid::wrap_offsets):
// |d| <= period/2.
vec3 min_image(vec3 d) {
  if (P.period.w == 0.0) return d;
  for (int k = 0; k < DIM; ++k) {
    float L = P.period[k], half_L = 0.5 * P.period[k];
    if (L <= 0.0) continue;
    d[k] = d[k] > half_L ? d[k] - L : d[k];
    d[k] = d[k] < -half_L ? d[k] + L : d[k];
  }
  return d;
}

// Along a periodic axis, leaving through one end is entering through the other.
float wrap_periodic(float x, int k) {
  return x >= P.wall_hi[k] ? x - P.period[k] : x < P.wall_lo[k] ? x + P.period[k] : x;
}

// Pushes a particle that a correction took through a container wall plane back onto it
// (periodic axes have no walls).
vec3 clamp_to_walls(vec3 x) {
  for (int k = 0; k < DIM; ++k)
    if (P.period[k] == 0.0) x[k] = x[k] < P.wall_lo[k] ? P.wall_lo[k] : x[k] > P.wall_hi[k] ? P.wall_hi[k] : x[k];
  return x;
}

// The safety net (FluidWorld::put_back_escaped): a non-finite or escaped position goes a
// quarter spacing inside and loses its outward velocity; returns whether it moved. Along a
// periodic axis a finite overshoot wraps instead.
bool put_back(inout vec3 x, inout vec3 v) {
  bool moved = false;
  for (int k = 0; k < DIM; ++k) {
    if (P.period[k] > 0.0 && !isnan(x[k]) && !isinf(x[k])) {
      x[k] = wrap_periodic(x[k], k);
      if (isnan(v[k]) || isinf(v[k])) { v[k] = 0.0; moved = true; }
      continue;
    }
    float lo = P.wall_lo[k], hi = P.wall_hi[k];
    if (!(x[k] >= lo)) { x[k] = lo + P.put_back_margin; v[k] = max(v[k], 0.0); moved = true; }
    else if (!(x[k] <= hi)) { x[k] = hi - P.put_back_margin; v[k] = min(v[k], 0.0); moved = true; }
    if (isnan(v[k]) || isinf(v[k])) v[k] = 0.0;
  }
  return moved;
}

// The stencil as rows of three cells along x: row r of 3 (2D) or 9 (3D) covers the cells
// [first, last) around `key`; their particles are contiguous in a start array.
#if DIM == 3
const int kRows = 9;
#else
const int kRows = 3;
#endif
uvec2 stencil_row(uint key, int r) {
#if DIM == 3
  int dy = r % 3 - 1, dz = r / 3 - 1;
#else
  int dy = r - 1, dz = 0;
#endif
  int k = int(key) + dz * P.grid_dims.x * P.grid_dims.y + dy * P.grid_dims.x;
  return uvec2(uint(k - 1), uint(k + 2));
}

// The candidate ranges of a pair loop: `for (r < stencil_count()) c = stencil_range(key, r)`.
// Without periodic axes, the rows above. With them (UniformGrid::for_each_periodic_range), the
// rows along y and z continue past the seam, and a row along x that crosses it is split into
// its three cells: three ranges per row, those a row does not need empty.
int stencil_count() { return P.period.w == 0.0 ? kRows : 3 * kRows; }

int wrap_cell(int a, int c) {  // interior cells are 1..dims-2
  if (P.period[a] == 0.0) return c;
  int n = P.grid_dims[a] - 2;
  return c < 1 ? c + n : c > n ? c - n : c;
}

uvec2 stencil_range(uint key, int r) {
  if (P.period.w == 0.0) return stencil_row(key, r);
  int row = r / 3, part = r % 3;
  int cx = int(key % uint(P.grid_dims.x));
  uint rest = key / uint(P.grid_dims.x);
  int cy = int(rest % uint(P.grid_dims.y)), cz = int(rest / uint(P.grid_dims.y));
#if DIM == 3
  int dy = row % 3 - 1, dz = row / 3 - 1;
#else
  int dy = row - 1, dz = 0;
#endif
  int y = wrap_cell(1, cy + dy), z = DIM == 3 ? wrap_cell(2, cz + dz) : 0;
  int base = (z * P.grid_dims.y + y) * P.grid_dims.x;
  bool split = P.period.x > 0.0 && (cx == 1 || cx == P.grid_dims.x - 2);
  if (!split) return part == 0 ? uvec2(uint(base + cx - 1), uint(base + cx + 2)) : uvec2(0u, 0u);
  int x = wrap_cell(0, cx + part - 1);
  return uvec2(uint(base + x), uint(base + x + 1));
}
