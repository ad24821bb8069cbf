#pragma once
// `--set key=value` on a scene document. Internal to src/scene.
#include <string>

#include "scene/json_reader.h"

namespace rtsph::scene_detail {

/// Writes `value` at `key` ("solver.time_step.dt", "obstacles[0].center") in a canonical
/// scene document. The value is read as the parameter's kind expects: "0,-9.81,0" for vectors,
/// bare words for enums and strings. Unknown keys and indices past an array's end throw
/// SceneError; the value itself is checked when the document is read back.
void set_override(Json& doc, const std::string& key, const std::string& value,
                  const std::string& source);

}  // namespace rtsph::scene_detail
