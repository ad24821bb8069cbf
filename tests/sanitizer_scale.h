// Shorter runs under a sanitizer. scripts/test-asan.sh exports RTSPH_SANITIZER=1; a test that
// runs many steps multiplies its simulated time by sanitizer_scale() there and keeps its checks
// (a comparison over fewer steps is just as strict).
#pragma once

#include <cstdlib>
#include <string>

namespace rtsph::test {

inline bool under_sanitizer() {
  const char* s = std::getenv("RTSPH_SANITIZER");
  return s && *s && std::string(s) != "0";
}

inline double sanitizer_scale() { return under_sanitizer() ? 0.25 : 1.0; }

}  // namespace rtsph::test
