// The parameter tables of the scene's array items: fluid blocks, obstacles, their keyframes and
// emitters (the scene-wide table is in params.cpp).
#include "scene/params.h"

#include "scene/params_field.h"
#include "solvers/simulation.h"

namespace rtsph {

using namespace params_detail;

const std::vector<FieldInfo<FluidBlock>>& fluid_block_fields() {
  static const std::vector<FieldInfo<FluidBlock>> table = {
      field<&FluidBlock::min>({.key = "min", .unit = "m", .min = -kLength, .max = kLength,
                               .help = "Lower corner; particles fill a lattice from min + spacing/2.",
                               .required = true}),
      field<&FluidBlock::max>({.key = "max", .unit = "m", .min = -kLength, .max = kLength,
                               .help = "Upper corner; the block must lie inside the domain.",
                               .required = true}),
      field<&FluidBlock::shape>({.key = "shape", .default_text = "box",
                                 .choices = {"box", "sphere"}, .choices_2d = {"rectangle", "circle"},
                                 .help = "box (rectangle) fills [min, max]; sphere (circle) fills "
                                         "the ball inscribed in it."}),
      field<&FluidBlock::velocity>({.key = "velocity", .unit = "m/s", .min = -kSpeed, .max = kSpeed,
                                    .help = "Initial velocity of the block's particles."}),
  };
  return table;
}

const std::vector<FieldInfo<ObstacleSpec>>& obstacle_fields() {
  static const std::vector<FieldInfo<ObstacleSpec>> table = {
      field<&ObstacleSpec::shape>({.key = "shape", .default_text = "box",
                                   .choices = {"box", "sphere"},
                                   .choices_2d = {"rectangle", "circle"},
                                   .help = "box/sphere in 3D, rectangle/circle in 2D."}),
      field<&ObstacleSpec::center>({.key = "center", .unit = "m", .min = -kLength, .max = kLength,
                                    .help = "Centre at t = 0; must lie inside the domain.",
                                    .required = true}),
      field<&ObstacleSpec::half_extents>({.key = "half_extents", .unit = "m", .min = 1e-6,
                                          .max = kLength, .default_vec = {0.1, 0.1, 0.1},
                                          .help = "Half the side lengths of a box/rectangle "
                                                  "(the full size is twice this)."}),
      field<&ObstacleSpec::radius>({.key = "radius", .unit = "m", .min = 1e-6, .max = kLength,
                                    .default_value = 0.1, .help = "Radius of a sphere/circle."}),
      field<&ObstacleSpec::motion>({.key = "motion.type", .default_text = "static",
                                    .choices = {"static", "velocity", "path"},
                                    .help = "static; velocity: constant motion.velocity and "
                                            "motion.angular_velocity; path: follows "
                                            "motion.keyframes."}),
      field<&ObstacleSpec::velocity>({.key = "motion.velocity", .unit = "m/s", .min = -kSpeed,
                                      .max = kSpeed, .help = "Constant velocity (velocity motion)."}),
      field<&ObstacleSpec::angular_velocity>({.key = "motion.angular_velocity", .unit = "rad/s",
                                              .min = -1000, .max = 1000,
                                              .help = "Rotation about the centre (velocity motion): "
                                                      "the axis is its direction, the rate its "
                                                      "length. 2D: one number, the rate about z.",
                                              .z_only_in_2d = true}),
  };
  return table;
}

const std::vector<FieldInfo<Keyframe>>& keyframe_fields() {
  static const std::vector<FieldInfo<Keyframe>> table = {
      field<&Keyframe::time_s>({.key = "time", .unit = "s", .min = 0, .max = kTime,
                                .help = "Time of the keyframe; strictly increasing.",
                                .required = true}),
      field<&Keyframe::position>({.key = "position", .unit = "m", .min = -kLength, .max = kLength,
                                  .help = "Obstacle centre; linear interpolation in between.",
                                  .required = true}),
      field<&Keyframe::angle_rad>({.key = "angle", .unit = "rad", .min = -1e4, .max = 1e4,
                                   .help = "Rotation about the z axis through the centre."}),
  };
  return table;
}

const std::vector<FieldInfo<EmitterSpec>>& emitter_fields() {
  static const std::vector<FieldInfo<EmitterSpec>> table = {
      field<&EmitterSpec::position>({.key = "position", .unit = "m", .min = -kLength, .max = kLength,
                                     .help = "Nozzle centre; must lie inside the domain.",
                                     .required = true}),
      field<&EmitterSpec::direction>({.key = "direction", .min = -kLength, .max = kLength,
                                      .default_vec = {1, 0, 0},
                                      .help = "Jet direction, normalised on use; must be non-zero."}),
      field<&EmitterSpec::speed>({.key = "speed", .unit = "m/s", .min = 0, .max = kSpeed,
                                  .min_exclusive = true, .default_value = 2,
                                  .help = "Exit speed of the jet."}),
      field<&EmitterSpec::width>({.key = "width", .unit = "m", .min = 1e-5, .max = 100,
                                  .default_value = 0.1,
                                  .help = "Nozzle width (2D) or diameter (3D); at least "
                                          "fluid.spacing."}),
      field<&EmitterSpec::rate>({.key = "rate", .unit = "1/s", .min = 0, .max = 1e9,
                                 .default_value = 0,
                                 .help = "Particles per second; 0 = continuous jet, a layer "
                                         "every spacing/speed."}),
      field<&EmitterSpec::start_s>({.key = "start", .unit = "s", .min = 0, .max = kTime,
                                    .default_value = 0, .help = "Time the jet starts."}),
      field<&EmitterSpec::stop_s>({.key = "stop", .unit = "s", .min = 0, .max = 1e30,
                                   .default_value = 1e30,
                                   .help = "Time the jet stops; after start."}),
      field<&EmitterSpec::max_particles>({.key = "max_particles", .min = 0, .max = 1e9,
                                          .default_value = 100000,
                                          .help = "The emitter stops after this many particles."}),
  };
  return table;
}

const std::vector<ArrayMeta>& spec_arrays() {
  static const std::vector<ArrayMeta> arrays = {
      {"fluid_blocks", "Boxes filled with fluid at t = 0."},
      {"obstacles", "Solid bodies sampled as boundary-particle shells; static or moving."},
      {"emitters", "Nozzles that add fluid while running."},
  };
  return arrays;
}

const ArrayMeta& keyframes_array() {
  static const ArrayMeta a{"motion.keyframes", "Keyframes of a path motion, sorted by time."};
  return a;
}

}  // namespace rtsph
