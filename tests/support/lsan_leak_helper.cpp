// Helper of the lsan_reports_own_leak test (leak-checked builds only; see tests/CMakeLists.txt):
// uses GL as rtsph does (a headless context through EGL, created and destroyed, so the driver's
// modules are loaded and, on failed probes, unloaded), then leaks one block from rtsph's own
// code. LeakSanitizer must report exactly that block: the driver's leaks are suppressed
// (tests/lsan.supp, tests/support/keep_modules_loaded.cpp), rtsph's are not.
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <string>

#ifdef RTSPH_LEAK_HELPER_GL
#include "render/gl_context.h"
#endif

namespace rtsph::test_support {

constexpr std::size_t kLeakedBytes = 4321;  // distinctive, so the test finds this very block

[[gnu::noinline]] void leak_on_purpose() {
  char* block = new char[kLeakedBytes];
  std::memset(block, 0x5a, kLeakedBytes);
  // Keeps the allocation (it is "used") and drops the only pointer to it.
  asm volatile("" : : "r"(block) : "memory");
}

}  // namespace rtsph::test_support

int main() {
#ifdef RTSPH_LEAK_HELPER_GL
  {
    std::string error;
    if (auto ctx = rtsph::render::HeadlessContext::create(&error))
      std::printf("lsan_leak_helper: %s\n", ctx->description().c_str());
    else
      std::printf("lsan_leak_helper: no GL context (%s)\n", error.c_str());
  }
#endif
  rtsph::test_support::leak_on_purpose();
  std::printf("lsan_leak_helper: leaked %zu bytes in rtsph::test_support::leak_on_purpose\n",
              rtsph::test_support::kLeakedBytes);
  return 0;
}
