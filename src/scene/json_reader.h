#pragma once
// JSON document -> SimSpec, checking every value against the parameter tables (types, ranges,
// enum spellings, vector lengths, unknown keys). Cross-field rules are in checks.h. Internal.
#include <nlohmann/json.hpp>
#include <string>

#include "solvers/spec.h"

namespace rtsph::scene_detail {

using Json = nlohmann::ordered_json;

/// Parses text to JSON, turning every failure (bad UTF-8, syntax, absurd nesting) into a
/// SceneError that names `source` and the line and column.
Json parse_json_text(const std::string& text, const std::string& source);

/// Reads a scene document; missing keys keep SimSpec's defaults.
SimSpec spec_from_json(const Json& doc, const std::string& source);

/// The canonical document of a spec: every key, in table order.
Json spec_to_json(const SimSpec& spec);

/// A JSON value as shown in error messages: compact and cut short when long.
std::string show(const Json& value);

}  // namespace rtsph::scene_detail
