#pragma once
// Scene files: JSON descriptions of a simulation (docs/scene-format.md), read into a validated
// SimSpec. Every failure is a SceneError with a one-line message; nothing here crashes on bad
// input.
#include <string>
#include <utility>
#include <vector>

#include "scene/scene_error.h"
#include "solvers/spec.h"

namespace rtsph {

/// A built-in scene name (see builtin_scenes()) or the path of a scene file. An existing file
/// wins over a built-in of the same name.
SimSpec load_scene(const std::string& name_or_path);

/// Parses and validates scene text. `source` names it in error messages (file name).
SimSpec parse_scene(const std::string& text, const std::string& source);

/// Applies `key=value` (e.g. "solver.time_step.dt=0.001", "gravity=0,-9.81,0",
/// "solver.eos=linear", "obstacles[0].radius=0.2") and re-validates the whole spec, so an
/// override is held to the same rules as the file. Strings need no quotes.
void apply_override(SimSpec& spec, const std::string& assignment,
                    const std::string& source = "--set");

/// (name, one-line description) of every built-in scene, sorted by name.
std::vector<std::pair<std::string, std::string>> builtin_scenes();

/// The JSON text of a built-in scene as shipped in scenes/, or empty if there is none.
std::string builtin_scene_text(const std::string& name);

/// Canonical JSON of the whole spec: every key, fixed order, exact numbers.
/// parse_scene(scene_to_json(s), ...) == s for any valid s.
std::string scene_to_json(const SimSpec& spec);

/// docs/scene-format.md, generated from the parameter tables.
std::string scene_format_markdown();

}  // namespace rtsph
