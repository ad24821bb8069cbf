#pragma once
// The property the scene fuzzer checks, shared by fuzz/scene_fuzz.cpp and the regression test
// tests/scene_fuzz_regress_test.cpp.
// Input: scene JSON text, optionally followed by a line "--set" and then one `key=value`
// override per line, so apply_override is covered too. Required:
//  - parsing and overriding never crash and throw nothing but SceneError, whose message is one
//    line;
//  - a spec that parses serialises canonically: scene_to_json(parse_scene(scene_to_json(s)))
//    == scene_to_json(s) (checkpoints identify scenes by the hash of this text).
#include <exception>
#include <optional>
#include <string>
#include <string_view>

#include "scene/scene.h"

namespace rtsph::fuzz {

inline std::optional<std::string> canonical_problem(const SimSpec& spec) {
  const std::string json = scene_to_json(spec);
  SimSpec again;
  try {
    again = parse_scene(json, "canonical.json");
  } catch (const SceneError& e) {
    return "canonical JSON of a valid spec does not parse: " + std::string(e.what());
  }
  if (scene_to_json(again) != json) return "canonical JSON does not round-trip: " + json;
  return std::nullopt;
}

/// Empty if the input is handled correctly, else what went wrong.
inline std::optional<std::string> scene_input_problem(std::string_view input) {
  constexpr std::string_view kSep = "\n--set\n";
  const std::size_t sep = input.find(kSep);
  try {
    SimSpec spec = parse_scene(std::string(input.substr(0, sep)), "fuzz.json");
    if (auto p = canonical_problem(spec)) return p;
    if (sep != std::string_view::npos) {
      std::string_view rest = input.substr(sep + kSep.size());
      while (!rest.empty()) {
        const std::size_t nl = rest.find('\n');
        const std::string line(rest.substr(0, nl));
        rest = nl == std::string_view::npos ? std::string_view{} : rest.substr(nl + 1);
        apply_override(spec, line);
        if (auto p = canonical_problem(spec)) return "after --set " + line + ": " + *p;
      }
    }
  } catch (const SceneError& e) {
    const std::string what = e.what();
    if (what.find('\n') != std::string::npos) return "multi-line SceneError: " + what;
  } catch (const std::exception& e) {
    return "exception other than SceneError: " + std::string(e.what());
  } catch (...) {
    return "non-standard exception";
  }
  return std::nullopt;
}

}  // namespace rtsph::fuzz
