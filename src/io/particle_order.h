#pragma once
// What every exporter does before writing: check the view holds the selected arrays and put
// the particles in id order.
#include <cstdint>
#include <vector>

#include "core/particles.h"
#include "io/exporter.h"

namespace rtsph::io {

/// Throws std::invalid_argument if the dimension is not 2 or 3 or a selected array is null.
void check_view(const ParticleView& view, const ExportOptions& options);

/// Indices into the view in ascending id order (ties and missing ids keep memory order).
std::vector<std::uint32_t> id_order(const ParticleView& view);

}  // namespace rtsph::io
