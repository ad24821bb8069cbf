// Scene files: built-ins load and round-trip exactly; every class of bad input is a one-line
// SceneError naming the file, the JSON path and the offending value.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <initializer_list>

#include "scene/scene.h"
#include "solvers/geometry.h"

namespace rtsph {
namespace {

template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const SceneError& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected a SceneError";
  return {};
}

void expect_parts(const std::string& msg, std::initializer_list<const char*> parts) {
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  for (const char* p : parts) EXPECT_NE(msg.find(p), std::string::npos) << "no '" << p << "' in: " << msg;
}

std::string parse_error(const std::string& text) {
  return error_of([&] { parse_scene(text, "tank.json"); });
}

// A valid 3D scene that the error cases below break one key at a time. `extra` may give one of
// its own top-level keys (dimension, domain, fluid_blocks) instead: a file gives each key once.
std::string tank(const std::string& extra = "", const std::string& block = R"([0,0,0], "max": [0.5,0.5,1])") {
  std::string out = "{";
  auto part = [&](const std::string& key, const std::string& text) {
    if (extra.find("\"" + key + "\":") != std::string::npos) return;  // extra gives it
    out += (out.size() > 1 ? ", " : "") + text;
  };
  part("dimension", R"("dimension": 3)");
  part("domain", R"("domain": {"min": [0,0,0], "max": [1,1,1]})");
  part("fluid_blocks", R"("fluid_blocks": [{"min": )" + block + "}]");
  return out + extra + "}";
}

TEST(SceneBuiltins, ListHasTheRequiredScenesWithDescriptions) {
  std::vector<std::string> names;
  for (const auto& [name, description] : builtin_scenes()) {
    names.push_back(name);
    EXPECT_FALSE(description.empty()) << name;
    EXPECT_EQ(description.find('\n'), std::string::npos);
  }
  for (const char* required : {"dam_break_2d", "dam_break_3d", "double_dam_break_3d",
                               "drop_into_pool_3d", "nozzle_obstacle_2d"})
    EXPECT_NE(std::find(names.begin(), names.end(), required), names.end()) << required;
  EXPECT_TRUE(std::is_sorted(names.begin(), names.end()));
}

TEST(SceneBuiltins, EachLoadsAndRoundTripsExactly) {
  for (const auto& [name, _] : builtin_scenes()) {
    SCOPED_TRACE(name);
    const SimSpec s = load_scene(name);
    EXPECT_EQ(s.name, name);
    const std::string json = scene_to_json(s);
    const SimSpec back = parse_scene(json, name + ".canonical");
    EXPECT_EQ(scene_to_json(back), json);
    EXPECT_EQ(back.domain_max, s.domain_max);
    EXPECT_EQ(back.gravity, s.gravity);
    EXPECT_EQ(back.fluid_blocks.size(), s.fluid_blocks.size());
  }
}

TEST(SceneBuiltins, ParticleCountsAreAsDocumented) {
  const std::pair<const char*, double> expected[] = {
      {"dam_break_2d", 5000}, {"dam_break_3d", 24000}, {"double_dam_break_3d", 27000},
      {"drop_into_pool_3d", 16800 + 3375}, {"hydrostatic_2d", 5000},
  };
  for (const auto& [name, count] : expected) EXPECT_EQ(count_particles(load_scene(name)).fluid, count) << name;
  const SimSpec nozzle = load_scene("nozzle_obstacle_2d");
  ASSERT_EQ(nozzle.emitters.size(), 1u);
  EXPECT_EQ(nozzle.emitters[0].max_particles, 8000);
  EXPECT_EQ(nozzle.obstacles.at(0).shape, ObstacleShape::Sphere);
  EXPECT_EQ(load_scene("nozzle_moving_obstacle_2d").obstacles.at(0).path.size(), 3u);
}

TEST(SceneBuiltins, FileOnDiskLoadsLikeTheBuiltin) {
  const std::string path = std::string(RTSPH_SOURCE_DIR) + "/scenes/dam_break_3d.json";
  EXPECT_EQ(scene_to_json(load_scene(path)), scene_to_json(load_scene("dam_break_3d")));
}

TEST(SceneParse, EmptyObjectGivesTheDefaults) {
  EXPECT_EQ(scene_to_json(parse_scene("{}", "empty.json")), scene_to_json(SimSpec{}));
}

TEST(SceneParse, NestedAndDottedKeysAreEquivalent) {
  const SimSpec a = parse_scene(R"({"solver": {"time_step": {"mode": "fixed", "dt": 0.001}}})", "a");
  const SimSpec b = parse_scene(R"({"solver.time_step.mode": "fixed", "solver": {"time_step.dt": 0.001}})", "b");
  EXPECT_EQ(a.time_step_mode, TimeStepMode::Fixed);
  EXPECT_EQ(a.dt, 0.001);
  EXPECT_EQ(scene_to_json(a), scene_to_json(b));
}

TEST(SceneParse, FullSceneRoundTrips) {
  const std::string text = R"({
    "name": "everything", "dimension": 3,
    "domain": {"min": [-1, 0, -1], "max": [1, 2, 1]},
    "fluid": {"spacing": 0.05, "rest_density": 998.2, "viscosity": 1.0e-5},
    "solver": {"eos": "linear", "speed_of_sound": 30, "stiffness": 900, "tait_gamma": 7,
               "kernel": "wendland_c2", "smoothing_ratio": 1.3, "artificial_viscosity": 0.1,
               "clamp_negative_pressure": false, "boundary_layers": 2,
               "time_step": {"mode": "fixed", "dt": 2.5e-4, "cfl": 0.3, "max_dt": 0.001}},
    "gravity": [0.1, -9.81, 0.2], "end_time": 3.3,
    "fluid_blocks": [{"min": [-1, 0, -1], "max": [0, 1, 0], "velocity": [1, 0, 0]}],
    "obstacles": [
      {"shape": "sphere", "center": [0.5, 1, 0], "radius": 0.2,
       "motion": {"type": "velocity", "velocity": [0, 0, 1], "angular_velocity": [0, 1, 0]}},
      {"shape": "box", "center": [0, 1, 0.5], "half_extents": [0.1, 0.2, 0.3],
       "motion": {"type": "path", "keyframes": [{"time": 0, "position": [0, 1, 0.5]},
                                                {"time": 1.5, "position": [0.5, 1, 0.5], "angle": 0.7}]}}],
    "emitters": [{"position": [0, 1.5, 0], "direction": [1, -1, 0], "speed": 3, "width": 0.2,
                  "rate": 500, "start": 0.5, "stop": 2, "max_particles": 1234}]})";
  const SimSpec s = parse_scene(text, "everything.json");
  EXPECT_EQ(s.kernel, KernelType::WendlandC2);
  EXPECT_EQ(s.eos, Eos::Linear);
  EXPECT_FALSE(s.clamp_negative_pressure);
  EXPECT_EQ(s.obstacles[1].path[1].angle_rad, 0.7);
  EXPECT_EQ(s.obstacles[0].motion, MotionKind::Velocity);
  EXPECT_EQ(s.emitters[0].max_particles, 1234);
  const std::string json = scene_to_json(s);
  EXPECT_EQ(scene_to_json(parse_scene(json, "canonical")), json);
}

TEST(SceneParse, TwoDimensionalShapesUseTheirOwnNames) {
  const SimSpec s = parse_scene(R"({"dimension": 2, "domain": {"max": [2, 1]},
      "obstacles": [{"shape": "rectangle", "center": [1, 0.5], "half_extents": [0.1, 0.2]}]})", "r.json");
  EXPECT_EQ(s.obstacles[0].shape, ObstacleShape::Box);
  EXPECT_NE(scene_to_json(s).find("\"rectangle\""), std::string::npos);
}

TEST(SceneParse, TwoDimensionalRotationIsOneNumber) {
  const std::string text = R"({"dimension": 2, "domain": {"max": [2, 1]},
      "obstacles": [{"shape": "circle", "center": [1, 0.5], "motion": {"type": "velocity", "angular_velocity": 1.5}}]})";
  const SimSpec s = parse_scene(text, "spin.json");
  EXPECT_EQ(s.obstacles[0].angular_velocity, (Vec3d{{0, 0, 1.5}}));
  EXPECT_EQ(scene_to_json(parse_scene(scene_to_json(s), "canonical")), scene_to_json(s));
  SimSpec t = s;
  apply_override(t, "obstacles[0].motion.angular_velocity=-2");
  EXPECT_EQ(t.obstacles[0].angular_velocity[2], -2);
  const std::string bad = R"({"dimension": 2, "obstacles": [{"center": [0.5, 0.5], "motion": {"angular_velocity": [0, 1]}}]})";
  expect_parts(error_of([&] { parse_scene(bad, "spin.json"); }), {"obstacles[0].motion.angular_velocity", "[0,1]", "about z"});
}

// ---- errors -------------------------------------------------------------------------------

TEST(SceneErrors, ExampleFromTheSpecIsExact) {
  EXPECT_EQ(parse_error(tank(R"(, "fluid": {"spacing": -0.1})")),
            "tank.json: fluid.spacing: -0.1: expected a number in [1e-05, 10] (m)");
}

TEST(SceneErrors, MissingFile) {
  expect_parts(error_of([] { load_scene("/nonexistent/dir/tank.json"); }),
               {"/nonexistent/dir/tank.json", "no such file or built-in scene", "dam_break_3d"});
  expect_parts(error_of([] { load_scene("dam_brake_3d"); }), {"dam_brake_3d", "no such file"});
}

TEST(SceneErrors, UnreadableFile) {
  const auto dir = std::filesystem::temp_directory_path() / ("rtsph_scene_test_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir / "tank.json");
  expect_parts(error_of([&] { load_scene((dir / "tank.json").string()); }), {"tank.json", "directory"});
  if (geteuid() != 0) {  // root reads anything
    const auto file = dir / "locked.json";
    std::ofstream(file) << "{}";
    std::filesystem::permissions(file, std::filesystem::perms::none);
    expect_parts(error_of([&] { load_scene(file.string()); }), {"locked.json", "cannot read"});
  }
  std::filesystem::remove_all(dir);
}

TEST(SceneErrors, MalformedJsonGivesLineAndColumn) {
  expect_parts(parse_error("{\n  \"fluid\": {\"spacing\": 0.02,}\n}"), {"tank.json", "line 2, column", "malformed JSON"});
  expect_parts(parse_error(""), {"tank.json", "line 1", "end of input"});
  expect_parts(parse_error("{\"a\": tru}"), {"tank.json", "line 1"});
  // A number past a double's range has no parse position from the library: found in the text.
  const std::string overflow = parse_error("{\n  \"fluid\": {\"spacing\": 1e999}\n}");
  expect_parts(overflow, {"tank.json", "line 2, column 24", "1e999", "number overflow"});
  EXPECT_EQ(overflow.find("json.exception"), std::string::npos) << overflow;
}

TEST(SceneErrors, DuplicateKeysAreNamed) {
  // The last of two keys would win silently: named with its path, inside arrays too.
  expect_parts(parse_error("{\"dimension\": 2, \"fluid\": {}, \"dimension\": 3}"),
               {"tank.json", "dimension: appears twice"});
  expect_parts(parse_error("{\"fluid\": {\"spacing\": 0.02, \"viscosity\": 0, \"spacing\": 0.01}}"),
               {"tank.json", "fluid.spacing: appears twice"});
  expect_parts(parse_error("{\"fluid_blocks\": [{\"min\": [0, 0]}, {\"max\": [1, [2]], \"min\": [0], \"max\": [1]}]}"),
               {"tank.json", "fluid_blocks[1].max: appears twice"});
  // Nested and dotted spellings of one parameter are the same key given twice.
  expect_parts(parse_error(tank(R"(, "fluid": {"spacing": 0.05}, "fluid.spacing": 0.02)")),
               {"tank.json", "fluid.spacing: 0.02: given twice (nested and as a dotted key)"});
  // The same key in other objects is fine (min and max in the domain and in the block).
  EXPECT_NO_THROW(parse_scene(tank(), "tank.json"));
}

TEST(SceneErrors, NonUtf8Input) {
  expect_parts(parse_error("{\n\"name\": \"caf\xe9\"}"), {"tank.json", "line 2, column 13", "0xE9", "UTF-8"});
  expect_parts(parse_error("{\"name\": \"\xed\xa0\x80\"}"), {"tank.json", "0xED", "UTF-8"});  // surrogate
}

TEST(SceneErrors, UnknownKeysSuggestTheNearest) {
  expect_parts(parse_error(tank(R"(, "fluid": {"spaceing": 0.02})")),
               {"tank.json", "fluid.spaceing", "0.02", "did you mean fluid.spacing?"});
  expect_parts(parse_error(tank(R"(, "gravty": [0, -9.81, 0])")), {"gravty", "did you mean gravity?"});
  expect_parts(parse_error(tank("", R"([0,0,0], "max": [0.5,0.5,1], "velocit": [0,0,0])")),
               {"fluid_blocks[0].velocit", "did you mean fluid_blocks[0].velocity?"});
  expect_parts(parse_error(tank(R"(, "zzzzzzzzzzzz": 1)")), {"zzzzzzzzzzzz", "unknown key", "fluid_blocks"});
}

TEST(SceneErrors, WrongTypes) {
  expect_parts(parse_error(tank(R"(, "fluid": {"spacing": "0.02"})")), {"tank.json", "fluid.spacing", "\"0.02\"", "expected a number"});
  expect_parts(parse_error(tank(R"(, "solver": {"clamp_negative_pressure": 1})")), {"solver.clamp_negative_pressure", ": 1:", "true or false"});
  expect_parts(parse_error(tank(R"(, "solver": 3)")), {"solver", "expected an object"});
  expect_parts(parse_error(tank(R"(, "obstacles": {"shape": "box"})")), {"obstacles", "expected an array"});
  expect_parts(parse_error(R"({"fluid_blocks": [7]})"), {"fluid_blocks[0]", ": 7:", "expected an object"});
  expect_parts(parse_error("[1, 2]"), {"(top level)", "[1,2]", "expected an object"});
  expect_parts(parse_error(tank(R"(, "dimension": 2.5)")), {"dimension", "2.5", "integer"});
}

TEST(SceneErrors, OutOfRange) {
  expect_parts(parse_error(tank(R"(, "solver": {"tait_gamma": 70})")), {"solver.tait_gamma", "70", "[1, 10]"});
  expect_parts(parse_error(tank(R"(, "gravity": [0, -9.81, 1e9])")), {"gravity", "1000000000", "[-1000, 1000]"});
  expect_parts(parse_error(tank(R"(, "dimension": 4)")), {"dimension", ": 4:", "[2, 3]"});
}

TEST(SceneErrors, EnumValueNotInTheList) {
  expect_parts(parse_error(tank(R"(, "solver": {"eos": "stiff"})")), {"solver.eos", "\"stiff\"", "\"tait\", \"linear\""});
  expect_parts(parse_error(tank(R"(, "solver": {"kernel": 1})")), {"solver.kernel", ": 1:", "\"cubic_spline\""});
  expect_parts(parse_error(tank(R"(, "obstacles": [{"shape": "circle", "center": [0.5,0.5,0.5]}])")),
               {"obstacles[0].shape", "\"circle\"", "\"box\", \"sphere\""});
  expect_parts(parse_error(R"({"dimension": 2, "obstacles": [{"shape": "box", "center": [0.5,0.5]}]})"),
               {"obstacles[0].shape", "\"box\"", "\"rectangle\", \"circle\""});
}

TEST(SceneErrors, WrongArrayLengthForTheDimension) {
  expect_parts(parse_error(R"({"dimension": 2, "domain": {"max": [1, 1, 1]}})"), {"domain.max", "[1,1,1]", "2 numbers"});
  expect_parts(parse_error(tank(R"(, "gravity": [0, -9.81])")), {"gravity", "[0,-9.81]", "3 numbers"});
}

TEST(SceneErrors, MinNotBelowMax) {
  expect_parts(parse_error(R"({"domain": {"min": [0, 1, 0], "max": [1, 1, 1]}})"), {"tank.json", "domain.max", "[1, 1, 1]", "domain.min"});
  expect_parts(parse_error(tank("", R"([0.5,0,0], "max": [0.2,0.5,1])")), {"fluid_blocks[0].max", "[0.2, 0.5, 1]", "greater than"});
}

TEST(SceneErrors, GeometryOutsideTheDomain) {
  expect_parts(parse_error(tank("", R"([0,0,0], "max": [2,1,1])")), {"tank.json", "fluid_blocks[0].max", "[2, 1, 1]", "inside the domain"});
  expect_parts(parse_error(tank(R"(, "obstacles": [{"center": [0.5, -1, 0.5]}])")), {"obstacles[0].center", "[0.5, -1, 0.5]", "inside"});
  expect_parts(parse_error(tank(R"(, "emitters": [{"position": [3, 0.5, 0.5]}])")), {"emitters[0].position", "[3, 0.5, 0.5]", "inside"});
  expect_parts(parse_error(tank(R"(, "obstacles": [{"center": [0.5, 0.5, 0.5], "motion": {"type": "path",
      "keyframes": [{"time": 0, "position": [0.5, 0.5, 0.5]}, {"time": 1, "position": [5, 0.5, 0.5]}]}}])")),
               {"obstacles[0].motion.keyframes[1].position", "[5, 0.5, 0.5]"});
}

TEST(SceneErrors, OtherCrossFieldRules) {
  expect_parts(parse_error(tank(R"(, "obstacles": [{"center": [0.5, 0.5, 0.5], "motion": {"type": "path",
      "keyframes": [{"time": 1, "position": [0.5, 0.5, 0.5]}, {"time": 1, "position": [0.6, 0.5, 0.5]}]}}])")),
               {"obstacles[0].motion.keyframes[1].time", ": 1:", "after the previous"});
  expect_parts(parse_error(tank(R"(, "obstacles": [{"center": [0.5, 0.5, 0.5], "motion": {"type": "path"}}])")),
               {"obstacles[0].motion.keyframes", "at least one keyframe"});
  expect_parts(parse_error(tank(R"(, "emitters": [{"position": [0.5, 0.5, 0.5], "direction": [0, 0, 0]}])")),
               {"emitters[0].direction", "non-zero"});
  expect_parts(parse_error(tank(R"(, "emitters": [{"position": [0.5, 0.5, 0.5], "start": 2, "stop": 1}])")),
               {"emitters[0].stop", ": 1:", "after start"});
  expect_parts(parse_error(tank(R"(, "fluid_blocks": [{"max": [1, 1, 1]}])")), {"fluid_blocks[0].min", "(missing)", "required"});
}

TEST(SceneErrors, FixedTimeStepMustBePositive) {
  expect_parts(parse_error(tank(R"(, "solver": {"time_step": {"mode": "fixed", "dt": 0}})")),
               {"tank.json", "solver.time_step.dt", ": 0:", "(0, 1]"});
  expect_parts(parse_error(tank(R"(, "solver": {"time_step": {"mode": "fixed", "dt": -1e-3}})")),
               {"solver.time_step.dt", "-0.001"});
}

TEST(SceneErrors, SceneLargerThanMemory) {
  const std::string msg = parse_error(R"({"fluid": {"spacing": 1e-5}, "domain": {"max": [1, 1, 1]}})");
  expect_parts(msg, {"tank.json", "fluid.spacing", "1e-05", "bytes", "physical memory"});
}

}  // namespace
}  // namespace rtsph
