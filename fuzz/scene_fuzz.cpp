// libFuzzer target for the scene parser (scripts/fuzz.sh builds and runs it). The property
// checked is in scene_fuzz_check.h; a violation aborts, so libFuzzer saves the input.
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "scene_fuzz_check.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  if (const auto problem = rtsph::fuzz::scene_input_problem(input)) {
    std::fprintf(stderr, "scene_fuzz: %s\n", problem->c_str());
    std::abort();
  }
  return 0;
}
