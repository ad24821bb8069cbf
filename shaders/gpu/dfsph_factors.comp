// DFSPH after each sort (the CPU's Dfsph::compute_factors; Bender & Koschier 2017): with walls
// mirroring P_i and the velocity relative to the wall (src/solvers/dfsph_solve.cpp says why),
//   1/alpha_i = |sum_j m grad W_ij + 2 sum_b Psi_b grad W_ib|^2 + sum_j |m grad W_ij|^2     (eq. 8)
// the neighbour count (fluid and boundary, the particle itself included: the divergence solve
// leaves thin neighbourhoods alone), the walls' gradient sum_b Psi_b grad W_ib and rate
// sum_b Psi_b v_b.grad W_ib. With with_density, also rho_i = sum_j m W_ij + sum_b Psi_b W_ib
// (Akinci et al. 2012, eq. 6) and 1/rho_i for the viscosity terms, in the same walk.
// factor.w: the density the clamped solve keeps, rho0, or with solver.dfsph.surface_density
// "lattice" rho0 tau(|c|), c = (sum_j m grad W_ij + sum_b Psi_b grad W_ib)/rho0 the colour
// gradient and tau the rest lattice's cut sums (the CPU's src/solvers/surface_density.h).
BUFFER_POS BUFFER_DENS BUFFER_FKEY BUFFER_FSTART BUFFER_BPOS BUFFER_BVEL BUFFER_BSTART BUFFER_WGRAD BUFFER_DFSPH_FACTOR
uniform float tiny;       // below this 1/alpha the particle has (almost) no neighbours
uniform int with_density;
uniform int cut_rows;          // 0: rho0 everywhere; else the rows of cut_table in use
uniform vec2 cut_table[RTSPH_CUT_ROWS];  // (|c| in 1/m, tau), ascending |c|, deepest first
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= P.fluid_count) return;
  vec3 xi = pos[i].xyz;
  uint key = fkey[i];
  float wf = 0.0, wb = 0.0, sq = 0.0, cnt = 0.0, rate = 0.0;
  vec3 gf = vec3(0.0), gb = vec3(0.0);
  for (int r = 0; r < stencil_count(); ++r) {
    uvec2 c = stencil_range(key, r);
    for (uint j = fstart[c.x]; j < fstart[c.y]; ++j) {
      vec3 d = min_image(xi - pos[j].xyz);
      float r2 = dot(d, d);
      if (r2 >= P.support2) continue;
      float G = kernel_g(r2);
      wf += kernel_w(r2);
      sq += G * G * r2;
      gf += G * d;
      cnt += 1.0;
    }
    for (uint j = bstart[c.x]; j < bstart[c.y]; ++j) {
      vec4 b = bpos[j];
      vec3 d = min_image(xi - b.xyz);
      float r2 = dot(d, d);
      if (r2 >= P.support2) continue;
      vec3 g = (b.w * kernel_g(r2)) * d;
      wb += b.w * kernel_w(r2);
      gb += g;
      rate += dot(g, bvel[j].xyz);
      cnt += 1.0;
    }
  }
  dvec3 f = dvec3(P.mass * gf), w = dvec3(gb);
  double denom = dot(f + 2.0lf * w, f + 2.0lf * w) + double(P.mass) * double(P.mass) * double(sq);
  float target = P.rho0;
  if (cut_rows > 0) {
    float c = float(length(f + w)) / P.rho0;
    float tau = cut_table[cut_rows - 1].y;
    for (int q = 1; q < cut_rows; ++q) {
      if (c <= cut_table[q].x) {
        vec2 a = cut_table[q - 1], b = cut_table[q];
        tau = a.y + (b.x > a.x ? (c - a.x) / (b.x - a.x) : 1.0) * (b.y - a.y);
        break;
      }
    }
    target = P.rho0 * min(1.0, tau);
  }
  factor[i] = vec4(denom > double(tiny) ? float(1.0lf / denom) : 0.0, cnt, rate, target);
  wgrad[i] = vec4(gb, 0.0);
  if (with_density != 0) {
    float rho = P.mass * wf + wb;
    dens[i].x = rho;
    dens[i].w = 1.0 / rho;
  }
}
