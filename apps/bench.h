#pragma once
// `rtsph bench`: the throughput table (cmd_bench.cpp) and the real-time capacity search
// (bench_realtime.cpp), both on the built-in dam break.
#include <string>
#include <vector>

#include "solvers/spec.h"

namespace rtsph::app {

struct BenchOptions {
  int dim = 3;
  std::string method = "wcsph";
  std::string backend = "cpu";  // cpu or gpu (auto = cpu for bench)
  std::string particles = "10000,60000";
  int threads = 0;
  int steps = 30;
  std::string json;
  std::string gravity;  // "direct" or "tree": the self-gravitating star instead of the dam break
  bool realtime = false;
  double window_s = 1.0;  // simulated time each real-time probe measures
  std::vector<std::string> sets;  // --set key=value on the benched scene (not fluid.spacing, solver.method)
};

/// The built-in dam break with its spacing chosen so the column holds about n particles, run by
/// `method`, with h = spacing and the cubic spline (the performance target's setup), then the
/// `--set` overrides (fluid.spacing and solver.method are refused: --particles and --method set them).
SimSpec dam_break_with(int dim, double n, const std::string& method,
                       const std::vector<std::string>& sets = {});

/// The n = 1 polytrope (`polytrope_star_3d`, gas with self-gravity by `gravity`: "direct" or
/// "tree") with its spacing chosen so the sphere holds about n particles.
SimSpec star_with(double n, const std::string& gravity);

/// Bisects on the particle count for the largest dam break that `method` advances at ≥ 1 s of
/// simulated time per second of wall time, over the first window_s simulated seconds.
int bench_realtime(const BenchOptions& o);

}  // namespace rtsph::app
