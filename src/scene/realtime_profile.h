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
/// The fluid particles a device steps in `seconds_per_substep`, from probes of its cost: on the
/// line t = a + b·N through the two probes whose times are nearest it (a GPU's cost per substep
/// has a fixed part, its dispatches and barriers, that dominates small sizes; 0 when that part
/// alone is over the time), or t ∝ N through the nearest probe when there is one probe or the
/// two do not rise with N. Never more than twice the largest size probed: the line is not
/// trusted far beyond what was measured. 0 when no probe has a positive time.
double particles_in_time(std::vector<StepProbe> probes, double seconds_per_substep);

/// What a device keeps in real time with a real-time profile's PBF: the fluid particles whose
/// median substep takes `share` of the real time it stands for, from probes of the profile at up
/// to four spacings, no finer than `finest` (m). A GPU's substep has a fixed cost (dispatches,
/// barriers) that dominates small sizes, so one probe at a CPU's size would say little: the first
/// probe is at the profile's spacing, each next one sized from particles_in_time of the probes so
/// far (at most 8 times the size before), until one is within 20% of the time.
/// probe(spec) builds a simulation of spec on the device, from rest, and returns its fluid
/// particles and median substep time (median_substep_seconds).
struct DeviceBudget {
  double particles = 0;  // particles_in_time of the probes
  double rate = 0;       // the same as fluid particle-substeps per second (realtime_budget's rate)
  std::vector<StepProbe> probes;
  std::string describe() const;  // "10350 particles 1.52 ms, 43000 particles 2.61 ms, ..."
};
DeviceBudget measure_device_budget(const SimSpec& profile, double share, double finest,
                                   const std::function<StepProbe(const SimSpec&)>& probe);
/// measure_device_budget for the viewer's workload: the built-in dam break of that dimension, its
/// real-time profile at the CPU reference budget to start from (10,350 particles in 3D), the
/// calm share of realtime_calm_share, no finer than kRealtimeFinest of the scene's spacing. The
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
/// on the machine"): 3D 0.74 and 0.78 on the two machines it was measured on. 2D is lower: its
/// 2 m column flows fast enough that the CFL bound splits the violent substeps, which a
/// measurement from rest does not see.
double realtime_calm_share(int dimension);

/// PBF's Jacobi iterations per substep in the profile: at least, and at most (realtime_profile).
inline constexpr int kRealtimePbfIterations = 3, kRealtimePbfMaxIterations = 4;

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
/// finer: where the budget holds more than the scene, shrink the spacing until the water fills
/// it, down to a quarter of the scene's (kRealtimeFinest). The GPU's budget does (it is measured
/// at the sizes it is used at); the CPU's does not, as its per-thread model was only measured on
/// two cores, and the scene's spacing is the finest it runs.
RealtimeProfile realtime_profile(const SimSpec& scene, int solver_threads, double rate_per_thread = 0,
                                 bool finer = false);
/// The finest spacing a real-time profile refines a scene to, over the scene's own.
inline constexpr double kRealtimeFinest = 0.25;

}  // namespace rtsph
