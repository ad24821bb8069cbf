// Parsing must never crash or throw anything but SceneError, whatever the input. A cheap
// deterministic mutation fuzzer over the built-in scenes plus hand-picked nasty inputs.
#include <gtest/gtest.h>

#include <random>

#include "scene/scene.h"

namespace rtsph {
namespace {

// Returns false if anything other than success or a one-line SceneError came out.
bool survives(const std::string& text) {
  try {
    SimSpec s = parse_scene(text, "fuzz.json");
    // A spec that parses must also serialise and parse back.
    parse_scene(scene_to_json(s), "fuzz.canonical");
  } catch (const SceneError& e) {
    return std::string(e.what()).find('\n') == std::string::npos;
  } catch (...) {
    return false;
  }
  return true;
}

TEST(SceneFuzz, NastyInputs) {
  const std::string deep(100000, '[');
  const std::vector<std::string> inputs = {
      "", " ", "null", "0", "\"x\"", "{", "}", "{}}", deep, "{\"a\":" + deep,
      std::string("{\"name\": \"a\0b\"}", 16), "{\"name\": \"\"}", "{\"name\": \"line\\nbreak\"}",
      "{\"fluid\": {\"spacing\": 1e400}}", "{\"fluid\": {\"spacing\": -1e400}}",
      "{\"dimension\": 99999999999999999999999}", "{\"dimension\": -0}", "{\"dimension\": 2.0}",
      "{\"emitters\": [{\"position\": [0.5,0.5,0.5], \"max_particles\": 1e300}]}",
      "{\"obstacles\": [{\"center\": [0.5,0.5,0.5], \"motion\": {\"keyframes\": {}}}]}",
      "{\"obstacles\": [{\"center\": [0.5,0.5,0.5], \"motion\": 5}]}",
      "{\"solver\": {\"time_step\": []}}", "{\"domain\": {\"min\": [null, 0, 0]}}",
      "\xef\xbb\xbf{}", "{\"\xf4\x90\x80\x80\": 1}", "{\"a\": \"\\ud800\"}",
      "{\"" + std::string(5000, 'k') + "\": 1}", "{\"name\": \"" + std::string(5000, 'n') + "\"}",
  };
  for (const auto& in : inputs) EXPECT_TRUE(survives(in)) << in.substr(0, 80);
}

TEST(SceneFuzz, MutatedBuiltins) {
  std::mt19937 rng(12345);
  const std::string alphabet = "{}[]\",:.-+eE0123456789 \n\tabcdefghijklmnopqrstuvwxyz_\\\x80\xff";
  int iterations = 0;
  for (const auto& [name, _] : builtin_scenes()) {
    const std::string base = builtin_scene_text(name);
    for (int i = 0; i < 400; ++i, ++iterations) {
      std::string t = base;
      const int edits = 1 + int(rng() % 4);
      for (int e = 0; e < edits && !t.empty(); ++e) {
        const std::size_t at = rng() % t.size();
        const char c = alphabet[rng() % alphabet.size()];
        switch (rng() % 4) {
          case 0: t[at] = c; break;
          case 1: t.insert(at, 1, c); break;
          case 2: t.erase(at, 1 + rng() % 8); break;
          default: t = t.substr(0, at); break;
        }
      }
      ASSERT_TRUE(survives(t)) << name << " mutation " << i << ":\n" << t;
    }
  }
  EXPECT_GT(iterations, 1000);
}

}  // namespace
}  // namespace rtsph
