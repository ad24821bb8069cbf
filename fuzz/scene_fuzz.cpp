// libFuzzer target for the scene parser (scripts/fuzz.sh builds and runs it).
// Input: scene JSON text, optionally followed by a line "--set" and then one `key=value`
// override per line, so apply_override is fuzzed too. Properties checked:
//  - parsing and overriding never crash and throw nothing but SceneError, with a one-line
//    message;
//  - a spec that parses serialises canonically: scene_to_json(parse_scene(scene_to_json(s)))
//    == scene_to_json(s) (checkpoints identify scenes by the hash of this text).
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "scene/scene.h"

namespace {

[[noreturn]] void fail(const char* what, const std::string& detail) {
  std::fprintf(stderr, "scene_fuzz: %s: %s\n", what, detail.c_str());
  std::abort();
}

void check_canonical(const rtsph::SimSpec& spec) {
  const std::string json = rtsph::scene_to_json(spec);
  rtsph::SimSpec again;
  try {
    again = rtsph::parse_scene(json, "canonical.json");
  } catch (const rtsph::SceneError& e) {
    fail("canonical JSON of a valid spec does not parse", e.what());
  }
  if (rtsph::scene_to_json(again) != json) fail("canonical JSON does not round-trip", json);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  constexpr std::string_view kSep = "\n--set\n";
  const std::size_t sep = input.find(kSep);
  const std::string text(input.substr(0, sep));
  try {
    rtsph::SimSpec spec = rtsph::parse_scene(text, "fuzz.json");
    check_canonical(spec);
    if (sep != std::string_view::npos) {
      std::string_view rest = input.substr(sep + kSep.size());
      while (!rest.empty()) {
        const std::size_t nl = rest.find('\n');
        const std::string line(rest.substr(0, nl));
        rest = nl == std::string_view::npos ? std::string_view{} : rest.substr(nl + 1);
        rtsph::apply_override(spec, line);
        check_canonical(spec);
      }
    }
  } catch (const rtsph::SceneError& e) {
    const std::string what = e.what();
    if (what.find('\n') != std::string::npos) fail("multi-line SceneError", what);
  }
  // Anything else thrown escapes and libFuzzer reports it as a crash (uncaught exception).
  return 0;
}
