#pragma once
// The one table of scene parameters. JSON parsing (key names, types, ranges), `--set key=value`,
// the generated docs/scene-format.md and the viewer's sliders all read it, so a parameter is
// described in exactly one place. Elements of the scene's arrays (fluid blocks, obstacles,
// emitters, keyframes) have small tables of the same shape.
#include <string>
#include <string_view>
#include <vector>

#include "solvers/spec.h"

namespace rtsph {

enum class ParamKind { Real, Int, Bool, Enum, Vec3, String };

/// What a parameter is, independent of where it is stored.
struct ParamMeta {
  std::string key{};                   // JSON path inside its owner, dot-separated
  ParamKind kind = ParamKind::Real;
  std::string unit{};                  // SI unit; empty when dimensionless
  double min = 0, max = 0;           // inclusive range (Real, Int, and each Vec3 component)
  bool min_exclusive = false;        // range is (min, max]
  double default_value = 0;          // Real, Int, Bool (0/1); Enum: index into choices
  Vec3d default_vec{};               // Vec3
  std::string default_text{};          // String
  std::vector<std::string> choices{};  // Enum, in the order of the C++ enum's values
  std::vector<std::string> choices_2d{};  // Enum spelling in 2D scenes when it differs
  std::string help{};
  bool live = false;                 // safe to change while running; otherwise applies on reset
  bool required = false;             // must be given in a scene file (array elements only)
  bool z_only_in_2d = false;         // Vec3 written as one number (its z) in 2D: rotations

  /// The valid spellings in a scene of this dimension.
  const std::vector<std::string>& choices_for(int dimension) const {
    return dimension == 2 && !choices_2d.empty() ? choices_2d : choices;
  }
};

/// A parameter plus its accessors into the struct that holds it. Numbers, booleans and enums
/// (as choice index) go through get/set; vectors through get_vec/set_vec; strings through
/// get_text/set_text. Accessors not matching `kind` are null.
template <class Owner>
struct FieldInfo : ParamMeta {
  double (*get)(const Owner&) = nullptr;
  void (*set)(Owner&, double) = nullptr;
  Vec3d (*get_vec)(const Owner&) = nullptr;
  void (*set_vec)(Owner&, const Vec3d&) = nullptr;
  std::string (*get_text)(const Owner&) = nullptr;
  void (*set_text)(Owner&, const std::string&) = nullptr;
};

using ParamInfo = FieldInfo<SimSpec>;

/// Scalar, vector and enum parameters of SimSpec, in documentation order.
const std::vector<ParamInfo>& parameter_table();
/// Fields of one element of `fluid_blocks`, `obstacles`, `emitters`, `obstacles[].motion.keyframes`.
const std::vector<FieldInfo<FluidBlock>>& fluid_block_fields();
const std::vector<FieldInfo<ObstacleSpec>>& obstacle_fields();
const std::vector<FieldInfo<EmitterSpec>>& emitter_fields();
const std::vector<FieldInfo<Keyframe>>& keyframe_fields();

/// An array of objects in a scene file, e.g. "fluid_blocks" in SimSpec.
struct ArrayMeta {
  std::string key;
  std::string help;
};
const std::vector<ArrayMeta>& spec_arrays();      // fluid_blocks, obstacles, emitters
const ArrayMeta& keyframes_array();                // motion.keyframes inside an obstacle

/// The SimSpec parameter with this key, or null.
const ParamInfo* find_param(std::string_view key);

/// Reads a parameter as a number (Real, Int, Bool as 0/1, Enum as choice index). A Vec3
/// component is addressed as `gravity.x`, `.y` or `.z`. Throws SceneError for unknown keys and
/// for String parameters.
double get_param(const SimSpec& spec, std::string_view key);
/// Sets a parameter from a number after checking its range (and, for Enum, the index);
/// throws SceneError (source "--set") if it does not fit. Cross-field rules (domain, memory) are
/// not checked here: apply_override() does the full validation.
void set_param(SimSpec& spec, std::string_view key, double value);
/// The value as `--set` would write it: numbers in shortest round-trip form, enums by name,
/// vectors as "x,y,z".
std::string get_param_text(const SimSpec& spec, std::string_view key);
void set_param_text(SimSpec& spec, std::string_view key, const std::string& value);

}  // namespace rtsph
