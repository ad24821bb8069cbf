#include "io/particle_order.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>

namespace rtsph::io {

void check_view(const ParticleView& view, const ExportOptions& options) {
  if (view.dim != 2 && view.dim != 3) throw std::invalid_argument("ParticleView: dimension must be 2 or 3");
  if (view.count == 0) return;
  auto need = [](const void* p, const char* what) {
    if (!p) throw std::invalid_argument(std::string("ParticleView: missing ") + what);
  };
  for (int k = 0; k < view.dim; ++k) need(view.x[k], "positions");
  if (options.velocity)
    for (int k = 0; k < view.dim; ++k) need(view.v[k], "velocities");
  if (options.density) need(view.density, "density");
  if (options.pressure) need(view.pressure, "pressure");
  if (options.id) need(view.id, "ids");
}

std::vector<std::uint32_t> id_order(const ParticleView& view) {
  const std::size_t n = view.count;
  std::vector<std::uint32_t> order(n);
  if (!view.id) {
    std::iota(order.begin(), order.end(), 0u);
    return order;
  }
  const std::uint32_t max_id = n ? *std::max_element(view.id, view.id + n) : 0;
  if (max_id >= 4 * n + 1024) {
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(), [&](auto a, auto b) { return view.id[a] < view.id[b]; });
    return order;
  }
  // Ids are nearly dense (0..n-1 plus emitted ones), so a counting sort is linear.
  std::vector<std::uint32_t> start(static_cast<std::size_t>(max_id) + 2, 0);
  for (std::size_t i = 0; i < n; ++i) ++start[view.id[i] + 1];
  std::partial_sum(start.begin(), start.end(), start.begin());
  for (std::size_t i = 0; i < n; ++i) order[start[view.id[i]]++] = static_cast<std::uint32_t>(i);
  return order;
}

}  // namespace rtsph::io
