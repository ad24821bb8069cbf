// The parameter table: defaults agree with SimSpec{}, keys are unique, and `--set` /
// get/set-by-key behave, including nested keys, vectors, enums and bad input.
#include <gtest/gtest.h>

#include <initializer_list>
#include <set>

#include "scene/params.h"
#include "scene/scene.h"
#include "solvers/simulation.h"

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

template <class Owner>
void expect_defaults_match(const std::vector<FieldInfo<Owner>>& table) {
  const Owner fresh{};
  std::set<std::string> keys;
  for (const auto& f : table) {
    SCOPED_TRACE(f.key);
    EXPECT_TRUE(keys.insert(f.key).second) << "duplicate key";
    EXPECT_FALSE(f.help.empty());
    switch (f.kind) {
      case ParamKind::Vec3: EXPECT_EQ(f.get_vec(fresh), f.default_vec); break;
      case ParamKind::String: EXPECT_EQ(f.get_text(fresh), f.default_text); break;
      case ParamKind::Enum:
        ASSERT_LT(f.default_value, double(f.choices.size()));
        if (f.get) {
          EXPECT_EQ(f.get(fresh), f.default_value);
        } else {
          EXPECT_EQ(f.get_text(fresh), f.choices[std::size_t(f.default_value)]);
        }
        if (!f.choices_2d.empty()) {
          EXPECT_EQ(f.choices_2d.size(), f.choices.size());
        }
        break;
      default:
        EXPECT_EQ(f.get(fresh), f.default_value);
        if (f.kind == ParamKind::Real || f.kind == ParamKind::Int) {
          EXPECT_LT(f.min, f.max);
          if (!f.required) {
            EXPECT_TRUE(f.default_value <= f.max && f.default_value >= f.min);
          }
        }
    }
  }
}

TEST(SceneParams, DefaultsInTheTablesAreTheStructDefaults) {
  expect_defaults_match(parameter_table());
  expect_defaults_match(fluid_block_fields());
  expect_defaults_match(obstacle_fields());
  expect_defaults_match(keyframe_fields());
  expect_defaults_match(emitter_fields());
}

TEST(SceneParams, TableHasTheSpecifiedKeys) {
  for (const char* key : {"name", "dimension", "domain.min", "domain.max", "domain.periodic", "fluid.spacing",
                          "fluid.rest_density", "fluid.viscosity", "fluid.surface_tension",
                          "fluid.adhesion", "solver.method", "solver.eos",
                          "solver.speed_of_sound", "solver.stiffness", "solver.tait_gamma",
                          "solver.kernel", "solver.smoothing_ratio", "solver.artificial_viscosity",
                          "solver.clamp_negative_pressure", "solver.time_step.mode",
                          "solver.time_step.cfl", "solver.time_step.dt", "solver.time_step.max_dt",
                          "solver.boundary_layers", "solver.pbf.time_step", "solver.pbf.substeps",
                          "solver.pbf.iterations", "solver.pbf.max_density_error",
                          "solver.pbf.max_iterations", "solver.pbf.cfl", "solver.pbf.relaxation",
                          "solver.pbf.omega", "solver.pbf.scorr_k", "solver.pbf.scorr_n",
                          "solver.pbf.scorr_dq", "solver.pbf.xsph", "solver.pbf.vorticity",
                          "solver.dfsph.max_density_error", "solver.dfsph.max_divergence_error",
                          "solver.dfsph.max_iterations", "solver.dfsph.chebyshev",
                          "solver.dfsph.surface_density", "solver.dfsph.pressure_stabilisation", "domain.open", "solver.gas.eta",
                          "solver.gas.smoothing", "solver.gas.global_b",
                          "solver.gas.eos", "solver.gas.polytropic_k", "solver.gas.gamma",
                          "solver.gas.damping", "solver.gas.spring", "solver.gas.self_gravity",
                          "gravitational_constant", "solver.gas.gravity_solver",
                          "solver.gas.theta", "gravity", "body_force", "end_time"})
    EXPECT_NE(find_param(key), nullptr) << key;
  std::set<std::string> live;
  for (const auto& p : parameter_table())
    if (p.live) live.insert(p.key);
  EXPECT_EQ(live, (std::set<std::string>{"fluid.viscosity", "fluid.surface_tension", "fluid.adhesion",
                                         "solver.artificial_viscosity", "solver.shifting",
                                         "solver.clamp_negative_pressure", "solver.time_step.mode",
                                         "solver.time_step.cfl", "solver.time_step.dt",
                                         "solver.time_step.max_dt", "gravity", "body_force",
                                         // every PBF and DFSPH parameter is read afresh each step
                                         "solver.pbf.time_step", "solver.pbf.substeps",
                                         "solver.pbf.iterations", "solver.pbf.max_density_error",
                                         "solver.pbf.max_iterations", "solver.pbf.cfl",
                                         "solver.pbf.relaxation", "solver.pbf.omega",
                                         "solver.pbf.scorr_k",
                                         "solver.pbf.scorr_n", "solver.pbf.scorr_dq",
                                         "solver.pbf.xsph", "solver.pbf.vorticity",
                                         "solver.dfsph.max_density_error",
                                         "solver.dfsph.max_divergence_error",
                                         "solver.dfsph.max_iterations", "solver.dfsph.chebyshev", "solver.dfsph.pressure_stabilisation",
                                         // the gas method reads these afresh each step
                                         "solver.gas.damping", "solver.gas.spring",
                                         "solver.gas.self_gravity", "solver.gas.theta"}));
  EXPECT_EQ(find_param("solver.method")->choices, solver_methods());
}

TEST(SceneParams, GetAndSetByKey) {
  SimSpec s;
  EXPECT_EQ(get_param(s, "fluid.spacing"), 0.02);
  set_param(s, "fluid.viscosity", 1e-3);
  EXPECT_EQ(s.viscosity, 1e-3);
  set_param(s, "gravity.y", -3.7);
  EXPECT_EQ(s.gravity[1], -3.7);
  EXPECT_EQ(get_param(s, "gravity.y"), -3.7);
  set_param(s, "solver.kernel", 3);
  EXPECT_EQ(s.kernel, KernelType::Gaussian);
  EXPECT_EQ(get_param(s, "solver.method"), 0);
  set_param(s, "solver.clamp_negative_pressure", 0);
  EXPECT_FALSE(s.clamp_negative_pressure);

  EXPECT_EQ(get_param_text(s, "solver.kernel"), "gaussian");
  EXPECT_EQ(get_param_text(s, "gravity"), "0,-3.7,0");
  EXPECT_EQ(get_param_text(s, "name"), "scene");
  set_param_text(s, "solver.eos", "linear");
  EXPECT_EQ(s.eos, Eos::Linear);
  set_param_text(s, "gravity", "1,2,3");
  EXPECT_EQ(s.gravity, (Vec3d{{1, 2, 3}}));
  set_param_text(s, "solver.time_step.dt", "0.001");
  EXPECT_EQ(s.dt, 0.001);

  const SimSpec before = s;
  expect_parts(error_of([&] { set_param(s, "fluid.spacing", -1); }), {"--set", "fluid.spacing", "-1", "[1e-05, 10]"});
  expect_parts(error_of([&] { set_param(s, "fluid.spacng", 1); }), {"fluid.spacng", "did you mean fluid.spacing?"});
  expect_parts(error_of([&] { set_param(s, "solver.eos", 2); }), {"solver.eos", "\"tait\""});
  expect_parts(error_of([&] { set_param_text(s, "solver.eos", "stiff"); }), {"solver.eos", "stiff"});
  expect_parts(error_of([&] { set_param_text(s, "fluid.spacing", "abc"); }), {"fluid.spacing", "abc"});
  expect_parts(error_of([&] { set_param_text(s, "fluid.spacing", "nan"); }), {"fluid.spacing", "nan"});
  expect_parts(error_of([&] { set_param_text(s, "gravity", "1,2"); }), {"gravity", "1,2", "3 numbers"});
  expect_parts(error_of([&] { get_param(s, "name"); }), {"name"});
  EXPECT_EQ(scene_to_json(s), scene_to_json(before));
}

TEST(SceneOverride, NestedVectorEnumAndArrayElements) {
  SimSpec s = load_scene("dam_break_3d");
  apply_override(s, "solver.time_step.dt=0.001");
  apply_override(s, "solver.time_step.mode=fixed");
  apply_override(s, "solver.eos=linear");
  apply_override(s, "gravity=0,-9.81,0.5");
  apply_override(s, "fluid.spacing=0.01");
  apply_override(s, "name=my run");
  apply_override(s, "solver.clamp_negative_pressure=false");
  apply_override(s, "fluid_blocks[0].velocity=[1, 0, 0]");
  EXPECT_EQ(s.dt, 0.001);
  EXPECT_EQ(s.time_step_mode, TimeStepMode::Fixed);
  EXPECT_EQ(s.eos, Eos::Linear);
  EXPECT_EQ(s.gravity, (Vec3d{{0, -9.81, 0.5}}));
  EXPECT_EQ(s.spacing, 0.01);
  EXPECT_EQ(s.name, "my run");
  EXPECT_FALSE(s.clamp_negative_pressure);
  EXPECT_EQ(s.fluid_blocks[0].velocity, (Vec3d{{1, 0, 0}}));

  SimSpec n = load_scene("nozzle_moving_obstacle_2d");
  apply_override(n, "obstacles[0].radius=0.2");
  apply_override(n, "obstacles[0].motion.keyframes[1].position=1.2,0.4");
  apply_override(n, "emitters[0].speed=3");
  apply_override(n, "gravity=0,-1");
  EXPECT_EQ(n.obstacles[0].radius, 0.2);
  EXPECT_EQ(n.obstacles[0].path[1].position[0], 1.2);
  EXPECT_EQ(n.emitters[0].speed, 3);
  EXPECT_EQ(n.gravity[1], -1);
}

TEST(SceneOverride, BadOverridesAreSceneErrorsAndLeaveTheSpecUnchanged) {
  SimSpec s = load_scene("dam_break_3d");
  const std::string before = scene_to_json(s);
  expect_parts(error_of([&] { apply_override(s, "fluid.spaceing=0.01"); }),
               {"--set", "fluid.spaceing", "0.01", "did you mean fluid.spacing?"});
  expect_parts(error_of([&] { apply_override(s, "fluid.spacing=abc"); }), {"--set", "fluid.spacing", "\"abc\"", "expected a number"});
  expect_parts(error_of([&] { apply_override(s, "fluid.spacing=-1"); }), {"fluid.spacing", "-1", "[1e-05, 10]"});
  expect_parts(error_of([&] { apply_override(s, "solver.eos=stiff"); }), {"solver.eos", "\"stiff\""});
  expect_parts(error_of([&] { apply_override(s, "solver.eos=3"); }), {"solver.eos", "\"3\""});
  expect_parts(error_of([&] { apply_override(s, "gravity=0,-9.81"); }), {"gravity", "[0,-9.81]", "3 numbers"});
  expect_parts(error_of([&] { apply_override(s, "obstacles[5].radius=1"); }), {"obstacles[5].radius", "no element 5"});
  expect_parts(error_of([&] { apply_override(s, "obstacles[x].radius=1"); }), {"obstacles[x].radius", "unknown key"});
  expect_parts(error_of([&] { apply_override(s, "fluid.spacing"); }), {"--set", "fluid.spacing", "key=value"});
  expect_parts(error_of([&] { apply_override(s, "fluid.spacing"); }), {"(no value)"});
  expect_parts(error_of([&] { apply_override(s, "=0.01"); }), {"--set", "=0.01", "(no key)", "key=value"});
  expect_parts(error_of([&] { apply_override(s, "fluid_blocks[0].max=9,9,9"); }), {"fluid_blocks[0].max", "inside the domain"});
  expect_parts(error_of([&] { apply_override(s, "solver.time_step.dt=0", "cli"); }), {"cli: solver.time_step.dt: 0:"});
  EXPECT_EQ(scene_to_json(s), before);
}

}  // namespace
}  // namespace rtsph
