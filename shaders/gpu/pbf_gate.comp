// PBF's stopping test on the device (the CPU's Pbf::solve_density_constraint loop), so that the
// host queues a batch of Jacobi iterations and reads the outcome back once per batch, not once
// per iteration. The gate is stats[RTSPH_STAT_GATE]: x = 1 while the solve goes on (the lambda
// pass returns at once when it is 0, and the correction only copies the positions along),
// y = iterations done, z = the last summed compression tested.
//   mode 0: a substep's solve starts: open, no iterations
//   mode 1: an iteration ran (if the gate was open): count it, then stop at `most`, or from
//           `least` on once the compression its lambda pass measured (stats[RTSPH_STAT_SOLVE].y,
//           reduce.comp mode 1) is within the tolerance: sum <= threshold, threshold = the
//           largest sum whose mean is (the host's sum_threshold); threshold < 0: no tolerance.
BUFFER_STATS
uniform int mode, least, most;
uniform double threshold;
void main() {
  if (gl_GlobalInvocationID.x != 0u) return;
  if (mode == 0) {
    stats[RTSPH_STAT_GATE] = dvec4(1.0lf, 0.0lf, 0.0lf, 0.0lf);
    return;
  }
  dvec4 g = stats[RTSPH_STAT_GATE];
  if (g.x == 0.0lf) return;
  double it = g.y + 1.0lf;
  bool tested = threshold >= 0.0lf && it >= double(least) && it < double(most);
  double sum = tested ? stats[RTSPH_STAT_SOLVE].y : 0.0lf;
  bool stop = it >= double(most) || (it >= double(least) && (threshold < 0.0lf || sum <= threshold));
  stats[RTSPH_STAT_GATE] = dvec4(stop ? 0.0lf : 1.0lf, it, sum, 0.0lf);
}
