// docs/scene-format.md is generated from the parameter tables so it cannot drift from the
// parser; a test compares the committed file with this output.
#include <fmt/format.h>

#include "scene/params.h"
#include "scene/scene.h"
#include "scene/values.h"

namespace rtsph {
namespace {

using scene_detail::format_number;

constexpr const char* kIntro = R"(# Scene format

A scene is a UTF-8 JSON file describing one simulation. Use it anywhere a scene is expected,
by path or by the name of a built-in scene:

    rtsph run scenes/dam_break_3d.json
    rtsph run dam_break_2d --set fluid.spacing=0.01 --set solver.eos=linear

This file is generated from the parameter table in `src/scene/params.cpp`
(`rtsph scenes --markdown`); do not edit it by hand.

## Rules

- SI units throughout (m, s, kg, m/s, m/s², Pa).
- Dotted keys below are nested objects, `"solver": {"eos": "tait"}`; the dotted name also works
  as a key, `"solver.eos": "tait"`. Missing keys take the defaults below. Unknown keys are
  errors, with the nearest known key suggested, and so is a key given twice: twice in one
  object, or both nested and dotted (JSON readers would keep the last silently).
- Enumerations are strings, never integers.
- Vectors are arrays with `dimension` numbers: `[x, y]` in 2D, `[x, y, z]` in 3D; y is up.
  Defaults below are written in 3D; a 2D scene uses their first two components.
- `domain.min` and `domain.max` are the walls of a closed box. Wall particles are placed
  outside the walls automatically; fluid blocks, emitters and obstacle centres must lie inside.
- A fluid block is filled on a lattice starting at `min + spacing/2`, so a block of length L
  holds L/spacing particles along that axis.
- Obstacles are shells of boundary particles. Boxes and rectangles are given by their centre
  and `half_extents` (half the side lengths); spheres and circles by centre and `radius`.
- Parameters marked *live* may be changed while a simulation runs (viewer sliders); the others
  apply on reset.
- `--set key=value` overrides any parameter after the file is read, with the same checks:
  `--set gravity=0,-9.81,0`, `--set solver.time_step.mode=fixed --set solver.time_step.dt=1e-4`,
  `--set obstacles[0].radius=0.2`.
- A scene whose estimated memory exceeds the machine's physical memory is refused.

Every error is one line, `<file>: <json path>: <value>: <what was expected>`, for example

    tank.json: fluid.spacing: -0.1: expected a number in [1e-05, 10] (m)

## Example

The built-in scene `dam_break_2d`:

```json
)";

std::string cell(std::string s) {
  std::string out;
  for (char c : s) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

std::string kind_text(const ParamMeta& m) {
  switch (m.kind) {
    case ParamKind::Real: return "number";
    case ParamKind::Int: return "integer";
    case ParamKind::Bool: return "boolean";
    case ParamKind::String: return "string";
    case ParamKind::Vec3: return m.z_only_in_2d ? "vector (2D: number)" : "vector";
    case ParamKind::Enum: break;
  }
  std::string list;
  for (const auto& c : m.choices) list += (list.empty() ? "" : ", ") + fmt::format("`\"{}\"`", c);
  if (!m.choices_2d.empty()) {
    list += " (2D: ";
    for (std::size_t i = 0; i < m.choices_2d.size(); ++i)
      list += (i ? ", " : "") + fmt::format("`\"{}\"`", m.choices_2d[i]);
    list += ")";
  }
  return list;
}

std::string default_text(const ParamMeta& m) {
  if (m.required) return "required";
  switch (m.kind) {
    case ParamKind::Real:
    case ParamKind::Int: return format_number(m.default_value);
    case ParamKind::Bool: return m.default_value != 0 ? "true" : "false";
    case ParamKind::String: return fmt::format("`\"{}\"`", m.default_text);
    case ParamKind::Enum: return fmt::format("`\"{}\"`", m.choices.at(std::size_t(m.default_value)));
    case ParamKind::Vec3: break;
  }
  return scene_detail::format_vec(m.default_vec, 3);
}

template <class Owner>
std::string table(const std::vector<FieldInfo<Owner>>& fields) {
  std::string s =
      "| key | type | unit | range | default | live | description |\n"
      "|---|---|---|---|---|---|---|\n";
  for (const auto& f : fields) {
    const bool ranged = f.kind == ParamKind::Real || f.kind == ParamKind::Int || f.kind == ParamKind::Vec3;
    s += fmt::format("| `{}` | {} | {} | {} | {} | {} | {} |\n", f.key, kind_text(f),
                     f.unit, ranged ? scene_detail::format_range(f) : "", default_text(f),
                     f.live ? "yes" : "", cell(f.help));
  }
  return s;
}

}  // namespace

std::string scene_format_markdown() {
  std::string s = kIntro;
  s += builtin_scene_text("dam_break_2d");
  if (!s.ends_with('\n')) s += '\n';
  s += "```\n\n## Built-in scenes\n\n| name | description |\n|---|---|\n";
  for (const auto& [name, description] : builtin_scenes())
    s += fmt::format("| `{}` | {} |\n", name, cell(description));
  s += "\n## Parameters\n\n" + table(parameter_table());
  const auto& arrays = spec_arrays();
  s += fmt::format("\n## `{}[]`\n\n{} Each element:\n\n", arrays[0].key, arrays[0].help);
  s += table(fluid_block_fields());
  s += fmt::format("\n## `{}[]`\n\n{} Each element:\n\n", arrays[1].key, arrays[1].help);
  s += table(obstacle_fields());
  s += fmt::format("\n### `{}[].{}[]`\n\n{} Each element:\n\n", arrays[1].key,
                   keyframes_array().key, keyframes_array().help);
  s += table(keyframe_fields());
  s += fmt::format("\n## `{}[]`\n\n{} Each element:\n\n", arrays[2].key, arrays[2].help);
  s += table(emitter_fields());
  return s;
}

}  // namespace rtsph
