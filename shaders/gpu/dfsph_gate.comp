// DFSPH's stopping test on the device (the CPU's Dfsph::solve loop condition), so that the host
// queues a batch of sweeps and reads the outcome back once per batch, not once per sweep. The
// gate is stats[RTSPH_STAT_GATE]: x = 1 while the solve goes on (the sweep, pressure kick and
// residual passes return at once when it is 0), y = sweeps done, z = the last residual sum.
//   mode 0: a solve starts: open, no sweeps
//   mode 1: the residual of the warm start is in stats[RTSPH_STAT_RESIDUAL].x: test it
//   mode 2: a sweep ran (if the gate was open): count it, then test its residual
// The test is the CPU's (error > tolerance || sweeps < least) && sweeps < most, with the mean
// error's division moved to the host: sum > threshold, threshold = tolerance * n.
BUFFER_STATS
uniform int mode, least, most;
uniform double threshold;
void main() {
  if (gl_GlobalInvocationID.x != 0u) return;
  dvec4 g = stats[RTSPH_STAT_GATE];
  if (mode == 0) {
    stats[RTSPH_STAT_GATE] = dvec4(1.0lf, 0.0lf, 0.0lf, 0.0lf);
    return;
  }
  if (g.x == 0.0lf) return;
  double sweeps = g.y + (mode == 2 ? 1.0lf : 0.0lf);
  double sum = stats[RTSPH_STAT_RESIDUAL].x;
  bool go = (sum > threshold || sweeps < double(least)) && sweeps < double(most);
  stats[RTSPH_STAT_GATE] = dvec4(go ? 1.0lf : 0.0lf, sweeps, sum, 0.0lf);
}
