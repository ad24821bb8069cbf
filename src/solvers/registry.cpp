// Solvers registered by name. A constant table: adding a method is one row.
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "solvers/geometry.h"
#include "solvers/dfsph.h"
#include "solvers/gas.h"
#include "solvers/pbf.h"
#include "solvers/wcsph.h"

namespace rtsph {

namespace {
struct SolverEntry {
  const char* name;
  std::unique_ptr<Simulation> (*make2)(const SimSpec&, int);
  std::unique_ptr<Simulation> (*make3)(const SimSpec&, int);
};
template <template <int> class S, int D>
std::unique_ptr<Simulation> make(const SimSpec& s, int threads) {
  return std::make_unique<S<D>>(s, threads);
}
constexpr std::array<SolverEntry, 4> kSolvers{{
    {"wcsph", &make<Wcsph, 2>, &make<Wcsph, 3>},
    {"pbf", &make<Pbf, 2>, &make<Pbf, 3>},
    {"dfsph", &make<Dfsph, 2>, &make<Dfsph, 3>},
    {"gas", &make<Gas, 2>, &make<Gas, 3>},
}};
}  // namespace

std::vector<std::string> solver_methods() {
  std::vector<std::string> names;
  for (const auto& e : kSolvers) names.emplace_back(e.name);
  return names;
}

// Bytes per particle of the WCSPH storage: fluid x,v,a (3D), ρ, p, id; scratch p/ρ², 1/ρ,
// permutation temp; grid keys, sorted keys and order. Boundary: x, v, local, Ψ, owner, grid.
// PBF and DFSPH add up to 2D + 3 floats per particle of their own, the gas method 11 + 3D.
std::size_t estimate_memory_bytes(const SimSpec& s) {
  const auto c = count_particles(s);
  const double D = s.dimension;
  // The gas method keeps 5 + 2D fields and 6 + D scratch arrays (gas.h).
  const double method_bytes = s.method == "wcsph" ? 0.0
                              : s.method == "gas" ? 4.0 * (11 + 3 * D)
                                                  : 4.0 * (2 * D + 3);
  const double fluid_bytes = 4.0 * (3 * D + 3) + 4.0 * 3 + 4.0 * 3 + method_bytes;
  const double boundary_bytes = 4.0 * (3 * D + 2) + 4.0 * 4;
  const double total = (c.fluid + c.emitted_max) * fluid_bytes + c.boundary * boundary_bytes +
                       c.grid_cells * 4.0 * 2;
  return total > 1.8e19 ? std::size_t(-1) : std::size_t(total);
}

std::unique_ptr<Simulation> make_simulation(const SimSpec& spec, int threads) {
  const auto it = std::find_if(kSolvers.begin(), kSolvers.end(),
                               [&](const SolverEntry& e) { return spec.method == e.name; });
  if (it == kSolvers.end()) throw std::invalid_argument("unknown solver method '" + spec.method + "'");
  if (spec.dimension != 2 && spec.dimension != 3)
    throw std::invalid_argument("dimension must be 2 or 3");
  return spec.dimension == 2 ? it->make2(spec, threads) : it->make3(spec, threads);
}

}  // namespace rtsph
