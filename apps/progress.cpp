#include "apps/progress.h"

#include <unistd.h>

#include <algorithm>

namespace rtsph::app {

Progress::Progress(std::string label, double total, bool quiet)
    : label_(std::move(label)), total_(total), quiet_(quiet), tty_(isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()), last_(start_) {}

void Progress::update(double done, const std::string& rate_text) {
  if (quiet_) return;
  const auto now = std::chrono::steady_clock::now();
  const double since_last = std::chrono::duration<double>(now - last_).count();
  if (since_last < (tty_ ? 0.1 : 5.0) && done < total_) return;
  last_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double frac = total_ > 0 ? std::clamp(done / total_, 0.0, 1.0) : 1.0;
  const double eta = frac > 0 ? elapsed * (1 - frac) / frac : 0;
  if (tty_) {
    constexpr int kWidth = 30;
    const int filled = int(frac * kWidth);
    std::string bar(std::size_t(filled), '#');
    bar.resize(kWidth, '-');
    std::fprintf(stderr, "\r%s [%s] %5.1f%%  t=%.3f/%.3f s  %s  ETA %.0f s\033[K", label_.c_str(),
                 bar.c_str(), 100 * frac, done, total_, rate_text.c_str(), eta);
  } else {
    std::fprintf(stderr, "%s: %.1f%%  t=%.3f/%.3f s  %s  ETA %.0f s\n", label_.c_str(), 100 * frac,
                 done, total_, rate_text.c_str(), eta);
  }
  std::fflush(stderr);
  drawn_ = true;
}

void Progress::finish() {
  if (quiet_ || !drawn_) return;
  if (tty_) std::fprintf(stderr, "\n");
  std::fflush(stderr);
}

}  // namespace rtsph::app
