// Regressions of the scene fuzzer (scripts/fuzz.sh): every input it ever flagged, inline, must
// now be handled (parsed, or refused with a one-line SceneError; canonical JSON round trip).
// The property is fuzz/scene_fuzz_check.h, shared with the fuzz target.
//
// To add one: the crashing input is build/fuzz/artifacts/crash-<sha1>; paste it below as a
// string literal (escape non-printable bytes), with the date and what was wrong.
//
// Fuzzing history: 2 × 60 s + 300 s with clang-14, ASan + UBSan, seeded with scenes/*.json
// and fuzz/scene.dict (about 2.4 million inputs, ~2,860 edges covered): no crash, no property
// violation. The inputs below are hand-picked from the paths the fuzzer reached (overrides
// after the "--set" separator, odd numbers, deep nesting) so they stay covered by ctest.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "../fuzz/scene_fuzz_check.h"

namespace rtsph {
namespace {

using std::string_literals::operator""s;

const std::vector<std::string>& regressions() {
  static const std::vector<std::string> inputs = {
      // Overrides after a valid scene: each must be applied or refused with a SceneError.
      "{\"dimension\": 2, \"domain\": {\"min\": [0, 0], \"max\": [1, 1]}}\n--set\nfluid.spacing=0.05\n"
      "gravity=0,-1\nsolver.time_step.mode=fixed\nsolver.time_step.dt=1e-300\n",
      "{\"dimension\": 2}\n--set\n=\n\n==\nfluid.spacing\nobstacles[99999999999].radius=1\n",
      "{}\n--set\nobstacles[0].radius=0.1\nemitters[-1].speed=1\nname=" + std::string(300, 'x') + "\n",
      "{}\n--set\nsolver.eos=linear\nsolver.stiffness=1e10\nsolver.kernel=gaussian\nend_time=1e6\n",
      "{}\n--set\ngravity=nan,0,0\nfluid.spacing=inf\nfluid.spacing=-0\nfluid.spacing=0x10\n",
      // Numbers at the edges of double.
      "{\"fluid\": {\"spacing\": 4.9e-324}}", "{\"fluid\": {\"spacing\": 1.7976931348623157e308}}",
      "{\"end_time\": 1e-320}", "{\"solver\": {\"time_step\": {\"cfl\": 1.0000000000000002}}}",
      "{\"gravity\": [1e308, 1e308, 1e308]}",
      "{\"emitters\": [{\"position\": [0.5, 0.5, 0.5], \"rate\": 1e9, \"max_particles\": 1000000000}]}",
      // Structure.
      "{\"obstacles\": [{\"center\": [0.5, 0.5, 0.5], \"motion\": {\"type\": \"path\", \"keyframes\": "
      "[{\"time\": 1, \"position\": [0.5,0.5,0.5]}, {\"time\": 1, \"position\": [0.5,0.5,0.5]}]}}]}",
      "{\"fluid_blocks\": [{\"min\": [0,0,0], \"max\": [1,1,1]}, {\"min\": [0,0,0], \"max\": [1,1,1]}]}",
      "{\"name\": \"a\", \"name\": \"b\"}", "{\"dimension\": 3, \"dimension\": 2}",
      std::string(2000, '{'), "[" + std::string(3000, '[') + "]", "{\"a\":\"\\u0000\"}",
      "\0{}"s, "{}\0"s, "{\"name\": \"\xc0\xaf\"}",
  };
  return inputs;
}

TEST(SceneFuzzRegress, InlineInputs) {
  for (const auto& in : regressions()) {
    const auto problem = fuzz::scene_input_problem(in);
    EXPECT_FALSE(problem.has_value()) << *problem << "\ninput: " << in.substr(0, 200);
  }
}

TEST(SceneFuzzRegress, BuiltinScenesAreCanonical) {
  for (const auto& [name, _] : builtin_scenes()) {
    const auto problem = fuzz::scene_input_problem(builtin_scene_text(name));
    EXPECT_FALSE(problem.has_value()) << name << ": " << *problem;
  }
}

// The corpus scripts/fuzz.sh grew locally, when there is one (not in a clean checkout).
TEST(SceneFuzzRegress, LocalFuzzCorpus) {
  const std::filesystem::path dir = std::filesystem::path(RTSPH_SOURCE_DIR) / "build/fuzz/corpus/scene";
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) GTEST_SKIP() << "no fuzz corpus at " << dir;
  int n = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec)) {
    std::ifstream in(e.path(), std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto problem = fuzz::scene_input_problem(text);
    EXPECT_FALSE(problem.has_value()) << e.path() << ": " << *problem;
    ++n;
  }
  std::printf("replayed %d corpus inputs\n", n);
}

}  // namespace
}  // namespace rtsph
