#pragma once
// The plain description of a simulation: what a scene file says, after parsing and validation
// (src/scene fills it; the solvers only read it). SI units throughout. Vectors are 3-component;
// 2D scenes use x and y and ignore z. Defaults here are the defaults of the parameter table.
#include <cstdint>
#include <string>
#include <vector>

#include "core/kernels.h"
#include "core/vec.h"

namespace rtsph {

enum class Eos { Tait, Linear };
enum class TimeStepMode { Cfl, Fixed };
enum class ObstacleShape { Box, Sphere };  // 2D: "rectangle" and "circle" map to these
enum class MotionKind { Static, Velocity, Path };

struct FluidBlock {
  Vec3d min{}, max{};     // m
  Vec3d velocity{};       // m/s
};

struct Keyframe {
  double time_s = 0;
  Vec3d position{};       // m, obstacle centre
  double angle_rad = 0;   // rotation about z (2D) or about `axis` (3D)
};

struct ObstacleSpec {
  ObstacleShape shape = ObstacleShape::Box;
  Vec3d center{};                  // m
  Vec3d half_extents{0.1, 0.1, 0.1};  // m, box/rectangle
  double radius = 0.1;             // m, sphere/circle
  MotionKind motion = MotionKind::Static;
  Vec3d velocity{};                // m/s, MotionKind::Velocity
  Vec3d angular_velocity{};        // rad/s about the centre (2D uses z)
  std::vector<Keyframe> path;      // MotionKind::Path, sorted by time, linear interpolation
};

struct EmitterSpec {
  Vec3d position{};                // m, nozzle centre
  Vec3d direction{1, 0, 0};        // jet direction (normalised on use)
  double speed = 2.0;              // m/s
  double width = 0.1;              // m, nozzle width (2D) or diameter (3D)
  double rate = 0;                 // particles/s; 0 = continuous jet (a layer every spacing/speed)
  double start_s = 0, stop_s = 1e30;
  std::int64_t max_particles = 100000;
};

struct SimSpec {
  std::string name = "scene";
  int dimension = 3;
  Vec3d domain_min{0, 0, 0}, domain_max{1, 1, 1};  // m, the container walls

  // fluid
  double spacing = 0.02;           // m, initial particle spacing
  double rest_density = 1000.0;    // kg/m³
  double viscosity = 1e-6;         // m²/s, kinematic (Morris et al. 1997 laminar term)

  // solver
  std::string method = "wcsph";
  Eos eos = Eos::Tait;
  double speed_of_sound = 0;       // m/s; 0 = automatic, 10·sqrt(2 g H) (Monaghan 1994)
  double stiffness = 0;            // m²/s² (= Pa per kg/m³) for the linear EOS; 0 = c0²
  double tait_gamma = 7.0;
  KernelType kernel = KernelType::CubicSpline;
  double smoothing_ratio = 1.0;    // h / spacing
  double artificial_viscosity = 0.02;  // Monaghan α (dimensionless)
  bool clamp_negative_pressure = true;  // avoids tensile clumping at the free surface
  TimeStepMode time_step_mode = TimeStepMode::Cfl;
  double cfl = 0.4;                // CFL number for 0.4·h/(c0 + |v|max)
  double dt = 1e-4;                // s, fixed-step mode
  double max_dt = 5e-3;            // s, upper bound in CFL mode
  int boundary_layers = 1;         // Akinci: one layer suffices; more for thin fast jets

  Vec3d gravity{0, -9.81, 0};      // m/s²
  std::vector<FluidBlock> fluid_blocks;
  std::vector<ObstacleSpec> obstacles;
  std::vector<EmitterSpec> emitters;
  double end_time = 2.0;           // s
};

/// Copies the parameters that are safe to change while a simulation runs, because the solver
/// reads them afresh every step. (Gravity also sets the automatic c0, once, when the solver is
/// built: changing it later changes the force, not c0.) The parameter table's `live` flags
/// (src/scene/params.cpp) name the same set; tests/scene_live_params_test.cpp holds them together.
inline void copy_live_parameters(const SimSpec& from, SimSpec& to) {
  to.viscosity = from.viscosity;
  to.artificial_viscosity = from.artificial_viscosity;
  to.clamp_negative_pressure = from.clamp_negative_pressure;
  to.time_step_mode = from.time_step_mode;
  to.cfl = from.cfl;
  to.dt = from.dt;
  to.max_dt = from.max_dt;
  to.gravity = from.gravity;
}

}  // namespace rtsph
