#include "scene/params.h"

#include "scene/params_field.h"
#include "solvers/simulation.h"

namespace rtsph {

using namespace params_detail;

const std::vector<ParamInfo>& parameter_table() {
  static const std::vector<ParamInfo> table = {
      field<&SimSpec::name>({.key = "name", .default_text = "scene",
                             .help = "Scene name, used in output file names and window titles."}),
      field<&SimSpec::dimension>({.key = "dimension", .min = 2, .max = 3, .default_value = 3,
                                  .help = "2 or 3. Sets the length of every vector in the file."}),
      field<&SimSpec::domain_min>({.key = "domain.min", .unit = "m", .min = -kLength, .max = kLength,
                                   .default_vec = {0, 0, 0},
                                   .help = "Lower corner of the container. The walls are closed; "
                                           "wall particles are placed outside them."}),
      field<&SimSpec::domain_max>({.key = "domain.max", .unit = "m", .min = -kLength, .max = kLength,
                                   .default_vec = {1, 1, 1},
                                   .help = "Upper corner of the container; each component must "
                                           "exceed domain.min."}),
      field<&SimSpec::periodic>({.key = "domain.periodic", .default_text = "none",
                                 .choices = {"none", "x", "y", "xy", "z", "xz", "yz", "xyz"},
                                 .help = "Axes that wrap around: a particle leaving through one face "
                                         "enters through the opposite one, neighbours see across "
                                         "the seam, and there are no walls on those axes. Each "
                                         "periodic extent must be a whole number of spacings and "
                                         "at least three kernel supports."}),
      field<&SimSpec::open>({.key = "domain.open", .default_value = 0,
                             .help = "Open space (the gas method's stars): no walls and no "
                                     "put-back; the domain only bounds the fluid blocks at t = 0, "
                                     "and the neighbour grid follows the particles' bounding box."}),
      field<&SimSpec::spacing>({.key = "fluid.spacing", .unit = "m", .min = 1e-5, .max = 10,
                                .default_value = 0.02,
                                .help = "Initial particle spacing. Halving it multiplies the "
                                        "particle count by 4 (2D) or 8 (3D)."}),
      field<&SimSpec::rest_density>({.key = "fluid.rest_density", .unit = "kg/m³", .min = 1e-6,
                                     .max = 1e6, .default_value = 1000,
                                     .help = "Rest density ρ0; sets the particle mass ρ0·spacing^d "
                                             "(the gas method: the initial density, in code "
                                             "units for the star scenes)."}),
      field<&SimSpec::viscosity>({.key = "fluid.viscosity", .unit = "m²/s", .min = 0, .max = 10,
                                  .default_value = 1e-6,
                                  .help = "Kinematic viscosity ν (Morris et al. 1997). Water: 1e-6.",
                                  .live = true}),
      field<&SimSpec::surface_tension>({.key = "fluid.surface_tension", .min = 0,
                                        .max = 1e3, .default_value = 0,
                                        .help = "Surface tension γ of Akinci, Akinci & Teschner 2013 "
                                                "(cohesion plus curvature; 0 = off), in the paper's mixed units. Not the "
                                                "physical σ: rtsph validate's static droplet "
                                                "calibrates σ(γ) (docs/validation.md). Every method.",
                                        .live = true}),
      field<&SimSpec::adhesion>({.key = "fluid.adhesion", .min = 0, .max = 1e3,
                                 .default_value = 0,
                                 .help = "Adhesion β of Akinci et al. 2013: the fluid's pull "
                                         "towards walls and obstacles (0 = off). Every method.",
                                 .live = true}),
      field<&SimSpec::method>({.key = "solver.method", .default_text = "wcsph",
                               .choices = solver_methods(),
                               .help = "Solver method: wcsph (weakly compressible, small explicit steps), "
                                       "pbf (position based fluids: large fixed steps, for "
                                       "real time), dfsph (divergence-free SPH: implicit, "
                                       "large steps, accurate) or gas (compressible, "
                                       "self-gravitating gas with adaptive smoothing lengths: "
                                       "stars; solver.gas.*)."}),
      field<&SimSpec::backend>({.key = "solver.backend", .default_text = "auto",
                                .choices = {"auto", "cpu", "gpu"},
                                .help = "Where the solver runs: cpu, gpu (OpenGL 4.3 compute; "
                                        "wcsph, pbf and dfsph) or auto (the command's default: the CPU for "
                                        "run and bench). --backend overrides it."}),
      field<&SimSpec::eos>({.key = "solver.eos", .default_text = "tait", .choices = {"tait", "linear"},
                            .help = "Equation of state: Tait p = B((ρ/ρ0)^γ - 1) or linear "
                                    "p = k(ρ - ρ0)."}),
      field<&SimSpec::speed_of_sound>({.key = "solver.speed_of_sound", .unit = "m/s", .min = 0,
                                       .max = 1e5, .default_value = 0,
                                       .help = "Numerical speed of sound c0; 0 = automatic, "
                                               "10·sqrt(2 g H) for ~1% density variation."}),
      field<&SimSpec::stiffness>({.key = "solver.stiffness", .unit = "m²/s²", .min = 0, .max = 1e10,
                                  .default_value = 0,
                                  .help = "Linear EOS stiffness k (Pa per kg/m³); 0 = c0²."}),
      field<&SimSpec::tait_gamma>({.key = "solver.tait_gamma", .min = 1, .max = 10,
                                   .default_value = 7, .help = "Tait exponent γ (7 for water)."}),
      field<&SimSpec::kernel>({.key = "solver.kernel", .default_text = "cubic_spline",
                               .choices = {"cubic_spline", "wendland_c2", "poly6_spiky", "gaussian"},
                               .help = "Smoothing kernel. Support is 2h, except 3h for gaussian."}),
      field<&SimSpec::smoothing_ratio>({.key = "solver.smoothing_ratio", .min = 0.5, .max = 3,
                                        .default_value = 1,
                                        .help = "Smoothing length over spacing, h/spacing."}),
      field<&SimSpec::artificial_viscosity>({.key = "solver.artificial_viscosity", .min = 0,
                                             .max = 2, .default_value = 0.02,
                                             .help = "Monaghan's α; damps noise at the cost of "
                                                     "extra dissipation. At walls and obstacles it "
                                                     "damps the approach only: water slides along "
                                                     "them freely (WCSPH, DFSPH).",
                                             .live = true}),
      field<&SimSpec::clamp_negative_pressure>({.key = "solver.clamp_negative_pressure",
                                                .default_value = 1,
                                                .help = "Clamp pressure at 0 so the free surface "
                                                        "does not clump (tensile instability).",
                                                .live = true}),
      field<&SimSpec::shifting>({.key = "solver.shifting", .min = 0, .max = 10, .default_value = 0,
                                 .help = "Particle shifting (Lind et al. 2012): each step moves particles "
                                         "by -A h |v| dt grad C (Skillen et al. 2013) to keep their "
                                         "arrangement uniform, with Lind's anti-clumping term; surface particles shift "
                                         "only along the surface. 0 = off; 1 keeps still water steady, 2 feeds on "
                                         "itself there. WCSPH and DFSPH, both backends.",
                                 .live = true}),
      field<&SimSpec::hydrostatic_start>({.key = "fluid.hydrostatic_start", .default_value = 0,
                                          .help = "WCSPH: start each fluid block compressed along gravity to the "
                                                  "density its equation of state gives the hydrostatic pressure "
                                                  "rho0 g depth (depth below the block's top), so water at rest "
                                                  "starts at rest instead of settling with a slosh. "
                                                  "Other methods keep rho0 and ignore it."}),
      field<&SimSpec::transport_velocity>({.key = "solver.transport_velocity", .min = 0, .max = 10,
                                           .default_value = 0,
                                           .help = "Transport-velocity formulation (Adami, Hu & Adams 2013): "
                                                   "particles move with v + dt a_b, a_b the push of a uniform "
                                                   "background pressure p_b = this · rho0 c0², which keeps their "
                                                   "arrangement uniform; 0 = off, 1 = Adami's p_b. WCSPH and DFSPH, both backends. "
                                                   "No free-surface treatment: for confined or periodic flows "
                                                   "(Taylor-Green)."}),
      field<&SimSpec::time_step_mode>({.key = "solver.time_step.mode", .default_text = "cfl",
                                       .choices = {"cfl", "fixed"},
                                       .help = "cfl: adaptive dt = cfl·h/(c0 + |v|max) (WCSPH) "
                                               "or cfl·spacing/max(|v|max, sqrt(|g|H)) (DFSPH, H the fluid's "
                                               "height), at most max_dt; "
                                               "fixed: always dt. PBF has its own step.",
                                       .live = true}),
      field<&SimSpec::cfl>({.key = "solver.time_step.cfl", .min = 0, .max = 1, .min_exclusive = true,
                            .default_value = 0.4, .help = "CFL number (cfl mode).", .live = true}),
      field<&SimSpec::dt>({.key = "solver.time_step.dt", .unit = "s", .min = 0, .max = 1,
                           .min_exclusive = true, .default_value = 1e-4,
                           .help = "Time step (fixed mode).", .live = true}),
      field<&SimSpec::max_dt>({.key = "solver.time_step.max_dt", .unit = "s", .min = 0, .max = 1,
                               .min_exclusive = true, .default_value = 5e-3,
                               .help = "Upper bound on the time step (cfl mode).", .live = true}),
      field<&SimSpec::boundary_layers>({.key = "solver.boundary_layers", .min = 1, .max = 4,
                                        .default_value = 1,
                                        .help = "Layers of wall particles (Akinci 2012: one "
                                                "suffices; more for thin fast jets)."}),
      field<&SimSpec::pbf_time_step>({.key = "solver.pbf.time_step", .unit = "s", .min = 1e-5,
                                      .max = 0.1, .default_value = 1.0 / 60,
                                      .help = "PBF frame step, split into solver.pbf.substeps.",
                                      .live = true}),
      field<&SimSpec::pbf_substeps>({.key = "solver.pbf.substeps", .min = 1, .max = 100,
                                     .default_value = 4,
                                     .help = "PBF substeps per frame step (4 keep a 2 m deep "
                                             "column standing at 4 iterations; 2 do not).",
                                     .live = true}),
      field<&SimSpec::pbf_iterations>({.key = "solver.pbf.iterations", .min = 1, .max = 100,
                                       .default_value = 4,
                                       .help = "Jacobi iterations of the density constraint per "
                                               "substep (at least: see "
                                               "solver.pbf.max_density_error).",
                                       .live = true}),
      field<&SimSpec::pbf_max_density_error>({.key = "solver.pbf.max_density_error", .min = 0,
                                              .max = 0.1, .default_value = 0.01,
                                              .help = "PBF iterates past solver.pbf.iterations "
                                                      "while the mean compression (ρ-ρ0)/ρ0 "
                                                      "its last iteration measured is above "
                                                      "this (0.01 = 1%); 0 = exactly "
                                                      "solver.pbf.iterations.",
                                              .live = true}),
      field<&SimSpec::pbf_max_iterations>({.key = "solver.pbf.max_iterations", .min = 1,
                                           .max = 1000, .default_value = 20,
                                           .help = "Cap on PBF's Jacobi iterations per substep "
                                                   "(reached: the substep ends with the error "
                                                   "it has; iterations are reported).",
                                           .live = true}),
      field<&SimSpec::pbf_cfl>({.key = "solver.pbf.cfl", .min = 0, .max = 10, .default_value = 1,
                                .help = "PBF substeps shrink so no particle moves more than "
                                        "cfl·spacing in one; 0 = never.",
                                .live = true}),
      field<&SimSpec::pbf_relaxation>({.key = "solver.pbf.relaxation", .min = 0, .max = 10,
                                       .default_value = 0.01,
                                       .help = "Constraint relaxation ε in λ = -C/(Σ|∇C|² + ε), "
                                               "relative to a full neighbourhood's Σ|∇C|².",
                                       .live = true}),
      field<&SimSpec::pbf_omega>({.key = "solver.pbf.omega", .min = 0, .max = 1, .default_value = 1,
                                  .help = "Jacobi weight ω of each iteration's λ. 1 = Macklin & "
                                          "Müller's full step, the fastest, but past the rest "
                                          "lattice's stability limit (0.71 in 3D, 0.93 in 2D "
                                          "for the cubic spline at h = spacing): water at rest "
                                          "keeps moving at a few cm/s. 0 = the stable weight "
                                          "from the kernel (0.64 in 3D, 0.84 in 2D for the "
                                          "cubic spline): water comes to rest, at up to 60% "
                                          "more iterations where it moves. With "
                                          "solver.clamp_negative_pressure off the weight is "
                                          "0.5, whatever this says.",
                                  .live = true}),
      field<&SimSpec::pbf_scorr_k>({.key = "solver.pbf.scorr_k", .min = 0, .max = 10,
                                    .default_value = 0.1,
                                    .help = "Artificial pressure s_corr = -k[(W(r)/W(Δq))^n - "
                                            "(W(r*)/W(Δq))^n]+ against clumping, on pairs closer "
                                            "than r*, where the kernel's gradient peaks (2h/3 for "
                                            "the cubic spline), so water at rest carries none (in "
                                            "units of a unit constraint's λ); 0 = off.",
                                    .live = true}),
      field<&SimSpec::pbf_scorr_n>({.key = "solver.pbf.scorr_n", .min = 1, .max = 8,
                                    .default_value = 4, .help = "Exponent n of s_corr.",
                                    .live = true}),
      field<&SimSpec::pbf_scorr_dq>({.key = "solver.pbf.scorr_dq", .min = 0, .max = 0.99,
                                     .default_value = 0.2,
                                     .help = "Δq of s_corr as a fraction of the kernel support.",
                                     .live = true}),
      field<&SimSpec::pbf_xsph>({.key = "solver.pbf.xsph", .min = 0, .max = 1,
                                 .default_value = 0.01,
                                 .help = "XSPH viscosity c (PBF's viscosity; fluid.viscosity and "
                                         "solver.artificial_viscosity do not apply to PBF).",
                                 .live = true}),
      field<&SimSpec::pbf_vorticity>({.key = "solver.pbf.vorticity", .unit = "m/s", .min = 0,
                                      .max = 10, .default_value = 0,
                                      .help = "Vorticity confinement ε: restores the swirl that "
                                              "PBF damps (0.01–0.05 for lively splashes); 0 = off.",
                                      .live = true}),
      field<&SimSpec::dfsph_max_density_error>({.key = "solver.dfsph.max_density_error",
                                                .min = 1e-6, .max = 0.1, .default_value = 1e-3,
                                                .help = "DFSPH constant-density solve stops at "
                                                        "this mean (ρ-ρ0)/ρ0 (0.001 = 0.1%).",
                                                .live = true}),
      field<&SimSpec::dfsph_max_divergence_error>({.key = "solver.dfsph.max_divergence_error",
                                                   .min = 1e-6, .max = 0.1, .default_value = 1e-3,
                                                   .help = "DFSPH divergence-free solve stops at "
                                                           "this mean (Dρ/Dt)·dt/ρ0.",
                                                   .live = true}),
      field<&SimSpec::dfsph_max_iterations>({.key = "solver.dfsph.max_iterations", .min = 1,
                                             .max = 10000, .default_value = 100,
                                             .help = "Iteration cap of each DFSPH solve: one that "
                                                     "reaches it ends with the error it has, and "
                                                     "the instability guard names it if the run "
                                                     "then goes unstable.",
                                             .live = true}),
      field<&SimSpec::dfsph_chebyshev>({.key = "solver.dfsph.chebyshev", .min = 0, .max = 0.999,
                                        .default_value = 0.95,
                                        .help = "Chebyshev acceleration of the density solve's "
                                                "Jacobi sweeps from the third sweep on (Wang "
                                                "2015), with clamped pressure only: the spectral "
                                                "radius ρ it assumes; a solve it acted in ends "
                                                "with one plain sweep; 0 = plain relaxed Jacobi.",
                                        .live = true}),
      field<&SimSpec::dfsph_surface_density>({.key = "solver.dfsph.surface_density",
                                              .default_text = "rest", .choices = {"rest", "lattice"},
                                              .help = "Where a free surface cuts a particle's kernel, "
                                                      "the density the clamped solve keeps: rest: ρ0, "
                                                      "so the surface band compacts until its cut "
                                                      "sums reach ρ0; lattice: the rest lattice's sum "
                                                      "under a flat surface at the particle's colour "
                                                      "gradient, so the band keeps the fluid's spacing. "
                                                      "For wide kernels (Wendland C2, h ≥ 1.5 "
                                                      "spacings): with fewer neighbours a disordered "
                                                      "interior reads as a cut (docs/validation.md)."}),
      field<&SimSpec::dfsph_pressure_stabilisation>(
          {.key = "solver.dfsph.pressure_stabilisation", .min = 0, .max = 10, .default_value = 0,
           .help = "β of a Laplacian of the pressure in DFSPH's density solve (as Brezzi & "
                   "Pitkäranta 1984 for finite elements): fixes the layer-alternating pressure a "
                   "lattice's gradient sums cannot see, which otherwise grows near a free surface "
                   "(stripes in the pressure colours); zero for a hydrostatic pressure. 0 = off; "
                   "1 pairs with solver.dfsph.surface_density \"lattice\" (docs/validation.md).",
           .live = true}),
      field<&SimSpec::gas_smoothing>({.key = "solver.gas.smoothing", .default_text = "adaptive",
                                      .choices = {"adaptive", "global"},
                                      .help = "Gas: adaptive hᵢ = η (mᵢ/ρᵢ)^(1/d) with the cubic "
                                              "spline and grad-h terms (Price 2012), or global: "
                                              "one h = b (⟨|x|²⟩ − |⟨x⟩|²)^½ for all particles "
                                              "with the Gaussian kernel (Gingold & Monaghan "
                                              "1977, eq. 4)."}),
      field<&SimSpec::gas_global_b>({.key = "solver.gas.global_b", .min = 0, .max = 10,
                                     .min_exclusive = true, .default_value = 0.1,
                                     .help = "Gas, global smoothing: b of h = b (⟨|x|²⟩ − "
                                             "|⟨x⟩|²)^½, the particles' positional spread."}),
      field<&SimSpec::gas_eta>({.key = "solver.gas.eta", .min = 0.5, .max = 3, .default_value = 1.2,
                                .help = "Gas: adaptive smoothing length hᵢ = η (mᵢ/ρᵢ)^(1/d), "
                                        "solved with the density by Newton–Raphson (Price 2012). "
                                        "1.2 gives ~58 neighbours in 3D with the cubic spline."}),
      field<&SimSpec::gas_eos>({.key = "solver.gas.eos", .default_text = "polytropic",
                                .choices = {"polytropic", "adiabatic"},
                                .help = "Gas: polytropic p = K ρ^γ (barotropic), or adiabatic "
                                        "p = (γ-1) ρ u with the internal energy u evolved and "
                                        "heated by the artificial viscosity (u starts at "
                                        "K ρ^(γ-1)/(γ-1))."}),
      field<&SimSpec::gas_k>({.key = "solver.gas.polytropic_k", .unit = "Pa·(m³/kg)^γ", .min = 0,
                              .max = 1e30, .min_exclusive = true, .default_value = 1,
                              .help = "Gas: polytropic constant K of p = K ρ^γ."}),
      field<&SimSpec::gas_gamma>({.key = "solver.gas.gamma", .min = 1, .max = 5,
                                  .min_exclusive = true, .default_value = 2,
                                  .help = "Gas: γ of p = K ρ^γ (2: the n = 1 polytrope) or of "
                                          "the ideal gas."}),
      field<&SimSpec::gas_damping>({.key = "solver.gas.damping", .unit = "1/s", .min = 0, .max = 1e6,
                                    .default_value = 0,
                                    .help = "Gas: velocity damping a = -damping·v, to relax a star "
                                            "into equilibrium; 0 = off.",
                                    .live = true}),
      field<&SimSpec::gas_spring>({.key = "solver.gas.spring", .unit = "1/s²", .min = 0, .max = 1e12,
                                   .default_value = 0,
                                   .help = "Gas: linear external force a = -spring·x toward the "
                                           "origin (the toy star's λ, Monaghan & Price 2004); "
                                           "0 = off.",
                                   .live = true}),
      field<&SimSpec::self_gravity>({.key = "solver.gas.self_gravity", .default_value = 0,
                                     .help = "Gas: self-gravity, softened by the kernel (Price & "
                                             "Monaghan 2007).",
                                     .live = true}),
      field<&SimSpec::gravitational_constant>({.key = "gravitational_constant", .unit = "m³/(kg·s²)",
                                               .min = 0, .max = 1e30, .default_value = 6.674e-11,
                                               .help = "G of the gas method's self-gravity: SI by "
                                                       "default; the star scenes use code units, "
                                                       "G = 1."}),
      field<&SimSpec::gravity_solver>({.key = "solver.gas.gravity_solver", .default_text = "direct",
                                       .choices = {"direct", "tree"},
                                       .help = "Gas: self-gravity by direct summation (exact, "
                                               "O(N²), up to ~20k particles) or the Barnes–Hut "
                                               "octree (3D)."}),
      field<&SimSpec::gravity_theta>({.key = "solver.gas.theta", .min = 0, .max = 1.5,
                                      .default_value = 0.5,
                                      .help = "Gas: the tree's opening angle θ (smaller: more "
                                              "accurate, slower).",
                                      .live = true}),
      field<&SimSpec::gravity>({.key = "gravity", .unit = "m/s²", .min = -1000, .max = 1000,
                                .default_vec = {0, -9.81, 0},
                                .help = "Gravitational acceleration; y is up.", .live = true}),
      field<&SimSpec::body_force>({.key = "body_force", .unit = "m/s²", .min = -1000, .max = 1000,
                                   .default_vec = {0, 0, 0},
                                   .help = "A uniform acceleration added to gravity, e.g. the "
                                           "stand-in for a pressure gradient driving a periodic "
                                           "channel (Poiseuille flow).",
                                   .live = true}),
      field<&SimSpec::end_time>({.key = "end_time", .unit = "s", .min = 0, .max = kTime,
                                 .min_exclusive = true, .default_value = 2,
                                 .help = "Simulated time at which `rtsph run` stops."}),
      field<&SimSpec::viewer_realtime>({.key = "viewer.realtime", .default_value = 0,
                                        .help = "`rtsph view` runs this scene in real time: "
                                                "method pbf, with fluid.spacing coarsened until "
                                                "the fluid fits what the viewer's solver threads "
                                                "step in real time. `rtsph view --accurate` (or "
                                                "the panel's checkbox) runs it as written. "
                                                "Other commands ignore it."}),
  };
  return table;
}

const ParamInfo* find_param(std::string_view key) {
  for (const auto& p : parameter_table())
    if (p.key == key) return &p;
  return nullptr;
}

}  // namespace rtsph
