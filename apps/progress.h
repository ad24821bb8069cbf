#pragma once
// Progress on stderr: a redrawn bar on a terminal, plain lines (about every 5 s) otherwise.
#include <chrono>
#include <cstdio>
#include <string>

namespace rtsph::app {

class Progress {
 public:
  Progress(std::string label, double total, bool quiet);
  /// done: simulated seconds (or steps) so far; rate_text: e.g. "812 steps/s".
  void update(double done, const std::string& rate_text);
  void finish();

 private:
  std::string label_;
  double total_;
  bool quiet_, tty_;
  std::chrono::steady_clock::time_point start_, last_;
  bool drawn_ = false;
};

}  // namespace rtsph::app
