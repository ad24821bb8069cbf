#pragma once
// The viewer's real-time profile (issue 9 §5): scenes with viewer.realtime set run with PBF, at
// a spacing coarse enough that the viewer's solver threads keep up with real time. The budget
// is measured, not derived: on the reference machine (docs/performance.md, "The viewer in real
// time"), and by the viewer on the machine it runs on (measure_particle_substeps_per_thread).
#include <functional>
#include <string>
#include <vector>

#include "solvers/spec.h"

namespace rtsph {

class Simulation;

/// Fluid particle-substeps per second one solver thread keeps up with in PBF, with the viewer
/// drawing beside it (Mesa llvmpipe on the other core), on the reference 2-core machine.
double realtime_particle_substeps_per_thread(int dimension);
/// The fluid particles (emitters' caps included) `solver_threads` keep in real time for this
/// PBF set-up: the rate above over its substeps per second (solver.pbf.substeps over
/// solver.pbf.time_step), so a scene with twice the substeps gets half the particles.
/// rate_per_thread: fluid particle-substeps per second and thread (0: the reference machine's,
/// realtime_particle_substeps_per_thread).
double realtime_budget(const SimSpec& pbf_spec, int solver_threads, double rate_per_thread = 0);

/// The fastest the water of a scene is expected to move, for the CFL bound on PBF's substeps: the
/// largest of a dam break's front speed 2·sqrt(|g|·H) (Ritter's, shallow water) for each block,
/// H the height of its top above the floor along gravity; each block's own speed after that fall,
/// sqrt(|v|² + 2|g|H); and each emitter's jet speed after its fall from the nozzle. The floor is
/// the container's, or the water's lowest point where the domain is open or periodic along
/// gravity. Zero with no gravity, no emitter and no block moving. jets_only: the emitters' jets
/// alone (the blocks still set an open container's floor).
double realtime_flow_speed(const SimSpec& spec, bool jets_only = false);
/// The substeps per second a PBF set-up takes in that flow: its frame's (solver.pbf.substeps over
/// solver.pbf.time_step), or, where more, what solver.pbf.cfl asks at realtime_flow_speed (no
/// particle moves more than cfl·spacing in a substep). At a GPU's sizes the CFL term rules: the
/// 3D dam break at 255,552 particles took 380 substeps in its first second, not 120.
double realtime_substeps_per_second(const SimSpec& pbf_spec, bool jets_only = false);

/// The median wall time (s) of a substep of `sim`, stepped on from where it is: one untimed
/// substep (it sizes the scratch), then at least five, on until wall_s (at most 200). The clock
/// is read after wait_idle(): a GPU backend only queues its work.
double median_substep_seconds(Simulation& sim, double wall_s);

/// One measurement of a device's substep cost at one size.
struct StepProbe {
  double particles = 0;  // fluid particles
  double seconds = 0;    // median wall time of a substep
};
/// `sim`'s fluid particles and median_substep_seconds.
StepProbe probe_substeps(Simulation& sim, double wall_s);
/// The most fluid particles N a device keeps in real time, from probes of its substep cost: its
/// substep at N takes `share` of the real time of one of the substeps per second that N's spacing
/// asks for, t(N)·substeps_at(N) = share. t reads the probes as a polyline that never falls with
/// N (a GPU's cost per substep has a fixed part, its dispatches and barriers, that dominates small
/// sizes; a slower probe below a faster one is noise), the end segments' lines beyond the ends,
/// t ∝ N from one probe. Never more than `largest` times the largest size probed: the line is not
/// trusted far beyond what was measured. 0 when the fixed part alone is over the time, or no probe
/// has a positive time. substeps_at rises with N (realtime_substeps_per_second, the spacing finer).
double particles_in_real_time(const std::vector<StepProbe>& probes, double share, double largest,
                              const std::function<double(double)>& substeps_at);

/// What a device keeps in real time with a real-time profile's PBF: the fluid particles whose
/// median substep takes `share` of the real time it stands for (1/realtime_substeps_per_second
/// at their spacing: the probes step from rest, at the frame's substeps, but the flow will ask for
/// more at fine spacings), from probes of the profile at up to four spacings, no finer than
/// `finest` (m). A GPU's substep has a fixed cost (dispatches,
/// barriers) that dominates small sizes, so one probe at a CPU's size would say little: the first
/// probe is at the profile's spacing, each next one sized from particles_in_real_time of the probes so
/// far (at most 8 times the size before), until one is within 20% of the time.
/// probe(spec) builds a simulation of spec on the device, from rest, and returns its fluid
/// particles and median substep time (median_substep_seconds).
struct DeviceBudget {
  double particles = 0;  // particles_in_real_time of the probes
  double rate = 0;       // the same as fluid particle-substeps per second, at its substeps per second
  std::vector<StepProbe> probes;
  std::string describe() const;  // "10350 particles 1.52 ms, 43000 particles 2.61 ms, ..."
};
DeviceBudget measure_device_budget(const SimSpec& profile, double share, double finest,
                                   const std::function<StepProbe(const SimSpec&)>& probe);
/// measure_device_budget for the viewer's workload: the built-in dam break of that dimension, its
/// real-time profile at the CPU reference budget to start from (10,350 particles in 3D) with
/// kDeviceProbeIterations per substep, the share of realtime_device_share, no finer than
/// kRealtimeFinest of the scene's spacing. The
/// viewer's GPU budget and `rtsph bench --realtime --backend gpu` both measure this.
DeviceBudget dam_break_device_budget(int dimension, const std::function<StepProbe(const SimSpec&)>& probe);

/// This machine's rate, measured: steps `profile_spec` (a profile's spec, on the CPU) from rest
/// with `threads` threads for about wall_s of wall time (at least a few substeps) and returns the
/// fluid particle-substeps per second and thread of its median substep.
double measure_particle_substeps_per_thread(const SimSpec& profile_spec, int threads, double wall_s);
/// The rate to budget with, given a measured one: the share of a calm substep's speed that held
/// real time in the viewer (the violent substeps cost more, and the drawing shares the cores),
/// bounded to [1/16, 2] times the reference machine's, so that one noisy measurement cannot make
/// a scene empty or huge.
double calibrated_rate(double measured_per_thread, int dimension);
/// The share above, measured in the viewer (docs/performance.md, "The viewer's budget, measured
/// on the machine" and "Session 23"). 3D: 0.85. On the 2-core Intel guest with 1.45-1.49e6
/// measured, fixed budgets held real time at 0.86 and 0.92 of it (3 runs each, never behind), 0.99
/// fell behind once or twice (RTF 0.99), 1.06 eighteen times (0.89); session 16 saw 0.76-0.78
/// hold on the same guest under heavy load, where the measurement moves by a quarter. 2D is lower: its
/// 2 m column flows fast enough that the CFL bound splits the violent substeps, which a
/// measurement from rest does not see.
double realtime_calm_share(int dimension);
/// The share of each substep's real time a GPU's budget gives its PBF substeps
/// (dam_break_device_budget). Lower than the CPU's in 3D: on a GPU the drawing runs on the same
/// device and thread, after the substeps, not on another core beside them (the viewer steps for
/// at most 1/60 s a frame, and at 243k particles a frame's drawing took ~12 ms more). `rtsph view` on an H200
/// (2026-11-27, docs/performance.md, "Session 22"), 3D dam break, 400 frames at 1280x720, the
/// budget at shares of 0.75, 0.59, 0.50 and 0.37: 248,820 particles, real-time factor 0.89
/// (behind 10 times), 208,444 0.93 (7), 181,779 0.98 (2), 144,540 1.00 (never behind, 41 fps).
/// 0.4 lies between the last two; it was not itself run in the window. 2D at 0.6: 34,453
/// particles, 1.00, never behind, 85 fps.
double realtime_device_share(int dimension);

/// PBF's Jacobi iterations per substep in the CPU's profile: at least, and at most
/// (realtime_profile). A device's profile keeps the scene's (4 to 20, to 1% mean compression).
inline constexpr int kRealtimePbfIterations = 3, kRealtimePbfMaxIterations = 4;
/// The iterations a device's budget probes run (dam_break_device_budget): what the 1% stop
/// averaged in the 3D dam break's first second at 31,944 to 506,715 particles, 6.4 to 6.9 (H100
/// and H200, `rtsph bench --realtime --backend gpu`); in 2D 6.6 to 6.9 at 7,938 to 64,082.
inline constexpr int kDeviceProbeIterations = 7;

struct RealtimeProfile {
  SimSpec spec;             // what the viewer runs
  bool applied = false;     // false: the scene is not marked viewer.realtime; spec as given
  double fluid_particles = 0, budget = 0;  // at the start plus what emitters may add
  double rate_per_thread = 0;  // fluid particle-substeps/s per thread the budget assumed
  // Where that rate came from, for describe(): the reference machine's unless a caller gave one
  // (the viewer: "measured on this machine", "--realtime-rate").
  std::string rate_source = "the reference machine's";
  std::string rate_per = "per solver thread";  // "on the GPU" where one device steps it
  std::string describe() const;  // one line for the terminal and the panel
};

/// The scene as the viewer runs it with `solver_threads` threads: unchanged unless
/// viewer.realtime is set; then method pbf with 3 to 4 iterations, and fluid.spacing grown until the
/// starting fluid plus the most its emitters may add fits the budget. Emitter caps scale with
/// the particle volume, so the scene keeps its amount of water. The result is validated like
/// any scene.
/// rate_per_thread as for realtime_budget (0: the reference machine's).
/// device: the rate is a device's (a GPU's), measured at the sizes it gives
/// (measure_device_budget). Then the scene keeps its iterations; where the budget holds more than
/// the scene, the spacing shrinks until the water fills it, down to a quarter of the scene's
/// (kRealtimeFinest); and the budget counts the substeps the CFL bound adds at a spacing
/// (realtime_substeps_per_second). The CPU's budget does none of these: 3 to 4 iterations
/// converge at its sizes, its per-thread model was only measured on two cores, the scene's
/// spacing is the finest it runs, and its calm share was measured in the viewer at the sizes it
/// gives, the CFL's extra substeps included (the bench's probes of 8,232 and 15,470 particles took
/// 123 and 136 a second).
RealtimeProfile realtime_profile(const SimSpec& scene, int solver_threads, double rate_per_thread = 0,
                                 bool device = false);
/// The finest spacing a real-time profile refines a scene to, over the scene's own.
inline constexpr double kRealtimeFinest = 0.25;

}  // namespace rtsph
