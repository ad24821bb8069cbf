// The GPU backend's shared layout: buffer binding points and the parameter block, written once
// for both C++ (src/gpu/*.cpp includes this file) and GLSL (gl_compute.cpp prepends this file's
// text to every compute shader in shaders/gpu/). Keep it to what both languages parse: #define,
// #if, structs of 4-component vectors and scalars in groups of four (std140 and C++ then agree;
// the static_asserts below check the sizes). ASCII only: GLSL reads the comments too.
#ifndef RTSPH_GPU_LAYOUT_H
#define RTSPH_GPU_LAYOUT_H

#ifdef __cplusplus
#include <cstdint>
namespace rtsph::gpu::glsl {
using uint = std::uint32_t;
struct alignas(16) vec4 { float x, y, z, w; };
struct alignas(16) ivec4 { std::int32_t x, y, z, w; };
struct alignas(32) dvec4 { double x, y, z, w; };
#endif

// Threads per workgroup of every per-particle pass (and the prefix scan's block size).
#define RTSPH_WG 256

// Shader storage bindings. Fluid arrays are in cell order after each sort.
#define RTSPH_B_POS 0        // vec4: x (m), w unused
#define RTSPH_B_VEL 1        // vec4: v (m/s)
#define RTSPH_B_ACC 2        // vec4: a (m/s^2)
#define RTSPH_B_DENS 3       // vec4: rho (kg/m^3), p (Pa), p/rho^2 (the symmetric pressure term), 1/rho
#define RTSPH_B_ID 4         // uint: stable particle id
#define RTSPH_B_FKEY 5       // uint: cell key of each fluid particle (sorted)
#define RTSPH_B_FSTART 6     // uint: first fluid particle of each cell; cells + 1 entries
#define RTSPH_B_BPOS 7       // vec4: boundary x, w = Psi (kg, Akinci 2012)
#define RTSPH_B_BVEL 8       // vec4: boundary v, w = depth behind the wall plane (m; fixed in the body)
#define RTSPH_B_BNORMAL 9    // vec4: wall normal into the fluid, w = owner (-1 wall, else obstacle)
#define RTSPH_B_BLOCAL 10    // vec4: position in the owner's body frame, w = face (below)
#define RTSPH_B_BSTART 11    // uint: first boundary sample of each cell
#define RTSPH_B_BPRESS 12    // float: p_b/rho0^2 extrapolated from the fluid (Adami 2012)
#define RTSPH_B_OBSTACLES 13 // Obstacle per obstacle
#define RTSPH_B_REDUCE 14    // dvec4 partials of a reduction; the put-back counter during drift
// The sort and scan's own buffers; the sorted payload is gathered through these bindings too.
#define RTSPH_B_KEYS_IN 15
#define RTSPH_B_VALS_IN 16
#define RTSPH_B_KEYS_OUT 17
#define RTSPH_B_VALS_OUT 18
#define RTSPH_B_COUNTS 19
#define RTSPH_B_SCAN 20
#define RTSPH_B_SCAN_SUMS 21
#define RTSPH_B_GATHER_IN0 22
#define RTSPH_B_GATHER_IN1 23
#define RTSPH_B_GATHER_IN2 24
#define RTSPH_B_GATHER_IN3 25
#define RTSPH_B_GATHER_OUT0 26
#define RTSPH_B_GATHER_OUT1 27
#define RTSPH_B_GATHER_OUT2 28
#define RTSPH_B_GATHER_OUT3 29
#define RTSPH_B_BKEY 30      // uint: cell key of each boundary sample (sorted)
#define RTSPH_B_STATS 31     // dvec4 results of the reductions (gpu_world_detail.h, StatSlot)
// Stats slots a pass reads on the device (the others are the host's; gpu_world_detail.h):
// PBF's summed compression (reduce.comp mode 1), DFSPH's residual sum (mode 6), and the gate of
// either method's stopping test (pbf_gate.comp, dfsph_gate.comp; a world runs one method).
#define RTSPH_STAT_SOLVE 5
#define RTSPH_STAT_RESIDUAL 7
#define RTSPH_STAT_GATE 8
#define RTSPH_BINDINGS 32
// Rows of DFSPH's cut-sum table (solver.dfsph.surface_density "lattice", dfsph_factors.comp): the
// layers of a flat surface a support of up to 15 spacings cuts.
#define RTSPH_CUT_ROWS 16
#define RTSPH_U_PARAMS 0     // uniform block binding of SphParams
// PBF's own arrays borrow the gather bindings (the sort rebinds those before each use; no PBF
// pass runs during a sort), so that no driver needs more than 32 storage bindings.
#define RTSPH_B_PRED RTSPH_B_GATHER_IN0       // vec4: predicted positions x*
#define RTSPH_B_LAMBDA RTSPH_B_GATHER_IN1     // vec2: lambda of this iteration, its sum over them
#define RTSPH_B_WGRAD RTSPH_B_GATHER_IN2      // vec4: sum_b Psi_b grad W_ib (the walls' gradient)
#define RTSPH_B_DENS_NEXT RTSPH_B_GATHER_IN3  // vec4: dens of the corrected positions
#define RTSPH_B_POS_NEXT RTSPH_B_GATHER_OUT0  // vec4: positions after a Jacobi correction
#define RTSPH_B_DELTA RTSPH_B_GATHER_OUT1     // vec4: XSPH and vorticity velocity change
#define RTSPH_B_OMEGA RTSPH_B_GATHER_OUT2     // vec4: vorticity
// PBF's neighbour lists borrow the sort's key and value bindings: built right after the sort and
// read by the constraint iterations, never during one.
#define RTSPH_B_NLIST RTSPH_B_KEYS_IN         // uint: fluid neighbours' indices, slot-major
#define RTSPH_B_NCOUNT RTSPH_B_VALS_IN        // uvec2: fluid and boundary neighbours found
#define RTSPH_B_BLIST RTSPH_B_KEYS_OUT        // uint: wall samples' indices, slot-major
// DFSPH's arrays borrow them the same way (WGRAD as PBF's). Only the warm start outlives a step;
// it is carried through the sort by a gather of its own.
#define RTSPH_B_DFSPH_SOLVE RTSPH_B_GATHER_IN0   // vec4: this sweep's change of P_i, the last sweep's
                                                 //   (Chebyshev), the solve's total P_i, the residual
#define RTSPH_B_DFSPH_FACTOR RTSPH_B_GATHER_IN1  // vec4: alpha_i (eq. 8), neighbour count,
                                                 //   sum_b Psi_b v_b.grad W_ib, unused
#define RTSPH_B_DFSPH_WARM RTSPH_B_GATHER_IN3    // vec4: last step's totals P dt^2 (density) and P dt
                                                 //   (divergence), unused, unused
// Surface tension's normals are written and read within one force stage, after the sort.
#define RTSPH_B_NORMAL RTSPH_B_GATHER_OUT3    // vec4: surface normal n_i (Akinci et al. 2013)
// WCSPH's transport velocity: written before the drift, carried through the sort by a gather of
// its own, read by the force stage; PBF (the only user of OMEGA) never runs it.
#define RTSPH_B_TDV RTSPH_B_GATHER_OUT2       // vec4: v~ - v of the transport velocity (m/s)

// Flags in SphParams.flags.
#define RTSPH_F_LINEAR_EOS 1u
#define RTSPH_F_CLAMP_NEGATIVE 2u
#define RTSPH_F_BRUSH 4u
#define RTSPH_F_WALL_HYDROSTATIC 8u
#define RTSPH_F_SURFACE 16u  // surface tension (gamma > 0) or adhesion (beta > 0) is on

// Everything a step's passes read that is constant over the step (std140 uniform block).
struct SphParams {
  dvec4 grid_origin;    // m, the neighbour grid's origin (double: the CPU computes keys in double
  dvec4 grid_inv_cell;  //   and the GPU must put every particle in the same cell)
  ivec4 grid_dims;      // cells per axis (z = 1 in 2D), w = total cells
  vec4 gravity;         // m/s^2, gravity + body force
  vec4 wall_lo;         // m, the container's wall planes (drift's contact); along a periodic
  vec4 wall_hi;         //   axis, the period's ends (a particle wraps there instead)
  vec4 period;          // m, xyz: the period along each periodic axis, 0 elsewhere; w: 1 when any
  vec4 surface;         // Akinci 2013: gamma, beta, cohesion constant, adhesion constant
  vec4 surface_b;       //   the support H (m), H^6/64 (m^6), 2 rho0 (kg/m^3), unused
  vec4 brush;           // xyz centre (m), w radius (m)
  vec4 kernel_a;        // the kernel's constants, as its CPU object holds them (core/kernels.h)
  vec4 kernel_b;
  float mass, support2, eps, ach;  // kg, m^2, eta^2 = 0.01 s^2 (m^2), alpha c0 h (m^2/s)
  float nu, dmin, inv_rho0, rho0;  // m^2/s, m (no-slip floor), m^3/kg, kg/m^3
  float tait_b, tait_gamma, stiffness, brush_strength;  // Pa, -, m^2/s^2, m/s^2
  float dt, kick_dt, put_back_margin, pad0;  // s, s (the kick before the drift), m
  uint fluid_count, boundary_count, flags, obstacle_count;
};

// An obstacle sample's face, blocal.w (obstacle_surface_point's `face`): 0 none, +-(k+1) the
// body-frame normal +-e_k, RTSPH_FACE_RADIAL the normalised body-frame position. move_boundary
// rotates it with the pose into bnormal.xyz.
#define RTSPH_FACE_RADIAL 4

// A rigid obstacle's pose and motion for the boundary transform (rows of R: body -> world).
struct Obstacle {
  vec4 r0, r1, r2;
  vec4 center;          // m
  vec4 velocity;        // m/s
  vec4 omega;           // rad/s
};

#ifdef __cplusplus
static_assert(sizeof(SphParams) == 320, "SphParams must match its std140 layout");
static_assert(sizeof(Obstacle) == 96, "Obstacle must match its std430 layout");
}  // namespace rtsph::gpu::glsl
#endif

#endif  // RTSPH_GPU_LAYOUT_H
