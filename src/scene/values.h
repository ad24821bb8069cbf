#pragma once
// Checking and spelling single parameter values, shared by the JSON reader, `--set` and the
// docs so that all three say the same thing about a parameter. Internal to src/scene.
#include <string>
#include <string_view>
#include <vector>

#include "scene/params.h"

namespace rtsph::scene_detail {

/// Shortest text that reads back as the same double ("0.02", "1e-05", "1e+30").
std::string format_number(double v);
/// "[x, y]" or "[x, y, z]".
std::string format_vec(const Vec3d& v, int dimension);
/// "[1e-05, 10]" or "(0, 1]".
std::string format_range(const ParamMeta& m);
/// The "what was expected" part of an error, e.g. "expected a number in [1e-05, 10] (m)".
std::string expected_text(const ParamMeta& m, int dimension);
/// Range (and integrality for Int) check of one number; false for NaN and infinities.
bool number_fits(const ParamMeta& m, double v);
/// Index of `name` among the choices valid in this dimension, or -1.
int choice_index(const ParamMeta& m, std::string_view name, int dimension);
/// The candidate closest to `key` by edit distance when close enough to be a likely typo.
std::string nearest_key(std::string_view key, const std::vector<std::string>& candidates);

}  // namespace rtsph::scene_detail
