#pragma once
// Rules that involve more than one value: geometry inside the domain, min < max, keyframe
// order, and whether the scene fits in memory. Internal to src/scene.
#include <cstddef>
#include <string>

#include "solvers/spec.h"

namespace rtsph::scene_detail {

/// Throws SceneError for the first broken rule, naming the JSON path of the value at fault.
void check_geometry(const SimSpec& spec, const std::string& source);

/// Throws SceneError (at fluid.spacing) when the solver's estimate exceeds `available` bytes.
void check_memory(const SimSpec& spec, const std::string& source, std::size_t available);

/// Physical memory of this machine in bytes.
std::size_t physical_memory_bytes();

}  // namespace rtsph::scene_detail
