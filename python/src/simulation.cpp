// rtsph.Simulation's engine side: stepping with the GIL released, particle arrays copied out in
// id order, validated writes, live parameters, checkpoints and exports through the CLI's code.
#include <fmt/format.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/filesystem.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>
#include <omp.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <vector>

#include "apps/run_checkpoint.h"
#include "apps/run_summary.h"
#include "binding.h"
#include "io/checkpoint.h"
#include "io/particle_order.h"
#include "scene/params.h"
#include "scene/scene.h"
#include "solvers/health.h"

namespace rtsph::py {
namespace {

using FloatArray = nb::ndarray<nb::numpy, float>;

PySimulation& checked(PySimulation& s) {
  if (!s.sim) throw std::runtime_error("the simulation was closed");
  return s;
}

/// A fresh numpy array owning `values` (n rows of `cols`; cols 0 = one dimension).
FloatArray to_numpy(std::vector<float>&& values, std::size_t n, std::size_t cols) {
  auto* data = new std::vector<float>(std::move(values));
  nb::capsule owner(data, [](void* p) noexcept { delete static_cast<std::vector<float>*>(p); });
  const std::size_t shape[2] = {n, cols};
  return FloatArray(data->data(), cols ? 2 : 1, shape, owner);
}

/// Copies `vectors` (one array per axis, `dim` of them) or `scalar` of the fluid into id order.
std::vector<float> gather_by_id(const ParticleView& v, const float* const* vectors, int dim,
                                const float* scalar) {
  const std::vector<std::uint32_t> order = io::id_order(v);
  const std::size_t cols = vectors ? std::size_t(dim) : 1;
  std::vector<float> out(v.count * cols);
  for (std::size_t r = 0; r < v.count; ++r)
    for (std::size_t k = 0; k < cols; ++k) out[r * cols + k] = vectors ? vectors[k][order[r]] : scalar[order[r]];
  return out;
}

FloatArray fluid_array(PySimulation& self, const char* what) {
  std::vector<float> values;
  std::size_t n = 0, cols = 0;
  {
    nb::gil_scoped_release release;
    Lock lock(checked(self).mutex);
    const ParticleView v = self.sim->fluid();
    n = v.count;
    const std::string w = what;
    if (w == "x" || w == "v") {
      cols = std::size_t(v.dim);
      values = gather_by_id(v, w == "x" ? v.x : v.v, v.dim, nullptr);
    } else {
      values = gather_by_id(v, nullptr, v.dim, w == "density" ? v.density : v.pressure);
    }
  }
  return to_numpy(std::move(values), n, cols);
}

/// Writes positions or velocities given in id order (float32, C order, shape (N, D)).
void set_fluid(PySimulation& self, nb::ndarray<const float, nb::ndim<2>, nb::c_contig> a, bool positions) {
  const char* name = positions ? "positions" : "velocities";
  nb::gil_scoped_release release;
  Lock lock(checked(self).mutex);
  const ParticleView v = self.sim->fluid();
  const std::size_t d = std::size_t(v.dim);
  if (a.shape(0) != v.count || a.shape(1) != d)
    throw std::invalid_argument(fmt::format("set_{}: expected an array of shape ({}, {}), got ({}, {})", name,
                                            v.count, d, a.shape(0), a.shape(1)));
  const float* in = a.data();
  for (std::size_t i = 0; i < v.count * d; ++i)
    if (!std::isfinite(in[i]))
      throw std::invalid_argument(fmt::format("set_{}: row {} holds a non-finite value ({})", name, i / d, in[i]));
  const std::vector<std::uint32_t> order = io::id_order(v);
  std::vector<float> axes[3];
  const float* ptrs[3] = {};
  for (std::size_t k = 0; k < d; ++k) {
    axes[k].resize(v.count);
    for (std::size_t r = 0; r < v.count; ++r) axes[k][order[r]] = in[r * d + k];
    ptrs[k] = axes[k].data();
  }
  self.sim->overwrite_fluid(positions ? ptrs : nullptr, positions ? nullptr : ptrs);
}

/// Steps until `until` (simulated seconds) or `max_steps`, whichever comes first. Each step runs
/// without the GIL; between steps the guard checks the state and Python gets to handle signals,
/// so Ctrl-C raises KeyboardInterrupt with the simulation intact at a step boundary.
long long advance(PySimulation& self, double until, long long max_steps) {
  long long done = 0;
  while (done < max_steps) {
    std::string issue;
    bool finished = false;
    {
      nb::gil_scoped_release release;
      Lock lock(checked(self).mutex);
      if (self.sim->time() >= until) {
        finished = true;
      } else {
        const auto t0 = std::chrono::steady_clock::now();
        self.sim->step();
        self.wall_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        ++self.steps_taken;
        ++done;
        if (auto msg = check_health_message(*self.sim, self.max_density_error)) issue = *msg;
      }
    }
    if (!issue.empty()) throw InstabilityError(issue);
    if (finished) break;
    if (PyErr_CheckSignals() != 0) throw nb::python_error();
  }
  return done;
}

Vec3d to_vec3(const std::vector<double>& v, int dim, const char* what) {
  if (v.size() != std::size_t(dim) && v.size() != 3)
    throw std::invalid_argument(fmt::format("{}: expected {} numbers, got {}", what, dim, v.size()));
  Vec3d out{};
  for (std::size_t k = 0; k < v.size(); ++k) {
    if (!std::isfinite(v[k])) throw std::invalid_argument(fmt::format("{}: component {} is not finite", what, k));
    out[k] = v[k];
  }
  return out;
}

nb::dict stats_dict(PySimulation& self) {
  app::RunSummary s;
  SimStats st;
  {
    nb::gil_scoped_release release;
    Lock lock(checked(self).mutex);
    s = app::make_summary(*self.sim, self.steps_taken, self.wall_s, self.threads);
    st = self.sim->stats();
  }
  nb::dict d;
  // The CLI's summary keys (rtsph run --stats-json), then the live figures of the last step.
  d["scene"] = s.scene;
  d["method"] = s.method;
  d["dimension"] = s.dimension;
  d["fluid_particles"] = s.fluid_particles;
  d["boundary_particles"] = s.boundary_particles;
  d["steps"] = s.steps;
  d["sim_time_s"] = s.sim_time_s;
  d["wall_s"] = s.wall_s;
  d["fluid_particle_steps_per_s"] = s.fluid_particle_steps_per_s;
  d["max_density_error"] = s.max_density_error;
  d["mean_density_error"] = s.mean_density_error;
  d["mean_pressure_iterations"] = s.mean_pressure_iterations;
  d["mean_divergence_iterations"] = s.mean_divergence_iterations;
  d["capped_steps"] = s.capped_steps;
  d["particles_put_back"] = s.particles_put_back;
  d["threads"] = s.threads;
  d["bytes"] = s.bytes;
  d["total_steps"] = st.steps;
  d["dt_s"] = st.dt_s;
  d["c0"] = st.c0;
  d["h"] = st.h;
  d["density_error"] = st.density_error;
  d["pressure_iterations"] = st.pressure_iterations;
  d["divergence_iterations"] = st.divergence_iterations;
  d["kinetic_energy_j"] = st.kinetic_energy_j;
  d["potential_energy_j"] = st.potential_energy_j;
  d["max_speed"] = st.max_speed;
  return d;
}

std::string export_frame(PySimulation& self, const std::string& dir, const std::string& format,
                         const std::string& attributes) {
  nb::gil_scoped_release release;
  Lock lock(checked(self).mutex);
  const std::string key = format + "\n" + std::filesystem::absolute(dir).lexically_normal().string();
  auto& exporter = self.exporters[key];
  if (!exporter) {
    io::ExportOptions eo = io::parse_attributes(attributes);
    // The surface formats (vdb, obj, ply-mesh) size their voxels from the scene, as `rtsph run` does.
    eo.surface.spacing_m = self.sim->spec().spacing;
    eo.surface.dimension = self.sim->spec().dimension;
    eo.surface.threads = self.threads;
    exporter = io::make_exporter(format, dir, eo);
  }
  const int frame = self.next_frame[key]++;
  exporter->write_frame(frame, self.sim->time(), self.sim->fluid());
  // The format picks the extension (vtk writes .vtp); report the file that was written.
  const std::string stem = fmt::format("frame_{:06d}", frame);
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.path().stem() == stem) return e.path().string();
  return (std::filesystem::path(dir) / stem).string();
}

}  // namespace

PySimulation::PySimulation(const PyScene& scene, int threads_, const std::string& backend_)
    : max_density_error(kDefaultMaxDensityError) {
  if (threads_ < 0) throw std::invalid_argument(fmt::format("threads: expected 0 (all cores) or more, got {}", threads_));
  if (backend_ != "cpu" && backend_ != "auto" && backend_ != "gpu")
    throw std::invalid_argument(fmt::format("backend '{}': expected cpu, gpu or auto", backend_));
  // auto is the CPU here, as for `rtsph run`: scripts are batch runs.
  backend = backend_ == "gpu" ? "gpu" : "cpu";
  threads = threads_ > 0 ? threads_ : omp_get_max_threads();
  nb::gil_scoped_release release;  // building the scene samples every particle
  try {
    sim = app::BackendSimulation::make(scene.spec, threads, backend);
  } catch (const app::BackendUnavailable& e) {
    // The CLI's line, worded for the keyword argument.
    std::string why = e.what();
    if (why.starts_with("--backend gpu")) why.replace(0, 13, "backend 'gpu'");
    throw std::invalid_argument(why);
  }
  // The lock makes a GPU simulation's context current on whichever thread takes it.
  sim.release_current();
}

PySimulation::~PySimulation() {
  // The GPU simulation's buffers belong to its context: free them with it current.
  std::lock_guard<std::mutex> lock(mutex.m);
  sim.reset();
}

void bind_simulation(nb::module_& m) {
  nb::class_<PySimulation>(m, "_Simulation")
      .def(nb::init<const PyScene&, int, const std::string&>(), nb::arg("scene"), nb::arg("threads") = 0,
           nb::arg("backend") = "cpu")
      .def("_advance", &advance, nb::arg("until"), nb::arg("max_steps"))
      .def_prop_ro("time", [](PySimulation& s) { Lock l(checked(s).mutex); return s.sim->time(); }, "Simulated time (s).")
      .def_prop_ro("dt", [](PySimulation& s) { Lock l(checked(s).mutex); return s.sim->stats().dt_s; },
                   "The last step's time step (s).")
      .def_prop_ro("step_count", [](PySimulation& s) { Lock l(checked(s).mutex); return s.sim->step_count(); })
      .def_prop_ro("dimension", [](PySimulation& s) { return checked(s).sim->dimension(); })
      .def_prop_ro("threads", [](PySimulation& s) { return s.threads; })
      .def_prop_ro("backend", [](PySimulation& s) { return s.backend; })
      .def_prop_ro("particle_count", [](PySimulation& s) { Lock l(checked(s).mutex); return s.sim->fluid().count; })
      .def_prop_ro("_scene", [](PySimulation& s) { Lock l(checked(s).mutex); return PyScene{s.sim->spec()}; })
      .def_prop_ro("stats", &stats_dict,
                   "The run summary (rtsph run --stats-json keys) and the last step's figures.")
      .def_prop_rw("max_density_error", [](PySimulation& s) { return s.max_density_error; },
                   [](PySimulation& s, double v) {
                     if (!(v > 0)) throw std::invalid_argument("max_density_error must be positive");
                     s.max_density_error = v;
                   })
      .def_prop_ro("positions", [](PySimulation& s) { return fluid_array(s, "x"); }, nb::rv_policy::reference,
                   "Fluid positions (m): a new float32 array of shape (N, D), rows in ascending particle id.")
      .def_prop_ro("velocities", [](PySimulation& s) { return fluid_array(s, "v"); }, nb::rv_policy::reference,
                   "Fluid velocities (m/s): a new float32 array of shape (N, D), rows in ascending particle id.")
      .def_prop_ro("density", [](PySimulation& s) { return fluid_array(s, "density"); }, nb::rv_policy::reference,
                   "Fluid density (kg/m³): a new float32 array of shape (N,), in particle-id order.")
      .def_prop_ro("pressure", [](PySimulation& s) { return fluid_array(s, "pressure"); }, nb::rv_policy::reference,
                   "Fluid pressure (Pa): a new float32 array of shape (N,), in particle-id order.")
      .def("_set_positions", [](PySimulation& s, nb::ndarray<const float, nb::ndim<2>, nb::c_contig> a) { set_fluid(s, a, true); })
      .def("_set_velocities", [](PySimulation& s, nb::ndarray<const float, nb::ndim<2>, nb::c_contig> a) { set_fluid(s, a, false); })
      .def("set_gravity",
           [](PySimulation& s, const std::vector<double>& g) {
             Lock l(checked(s).mutex);
             s.sim->set_gravity(to_vec3(g, s.sim->dimension(), "set_gravity"));
           },
           nb::arg("gravity"), "Gravity in m/s² (D or 3 numbers); takes effect at the next step.")
      .def("move_obstacle",
           [](PySimulation& s, int index, const std::vector<double>& c) {
             Lock l(checked(s).mutex);
             const int n = int(s.sim->spec().obstacles.size());
             if (index < 0 || index >= n)
               throw std::out_of_range(fmt::format("move_obstacle: index {} is not in [0, {})", index, n));
             s.sim->move_obstacle(index, to_vec3(c, s.sim->dimension(), "move_obstacle"));
           },
           nb::arg("index"), nb::arg("center"),
           "Moves obstacle `index` kinematically to `center` over the next step.")
      .def("obstacle_center",
           [](PySimulation& s, int index) {
             Lock l(checked(s).mutex);
             const int n = int(s.sim->spec().obstacles.size());
             if (index < 0 || index >= n)
               throw std::out_of_range(fmt::format("obstacle_center: index {} is not in [0, {})", index, n));
             const Vec3d c = s.sim->obstacle_center(index);
             return std::vector<double>(c.c.begin(), c.c.begin() + s.sim->dimension());
           },
           nb::arg("index"))
      .def("_set_parameter",
           [](PySimulation& s, const std::string& key, const std::string& text) {
             Lock l(checked(s).mutex);
             const ParamInfo* p = find_param(key);
             if (!p) throw SceneError("set_parameter", fmt::format("{}: no such parameter (see docs/scene-format.md)", key));
             if (!p->live)
               throw std::invalid_argument(fmt::format("{} is not a live parameter: build a new scene with it, "
                                                       "rtsph.scene(name, **{{'{}': value}})", key, key));
             SimSpec spec = s.sim->spec();
             apply_override(spec, key + "=" + text, "set_parameter");
             if (key == "gravity") s.sim->set_gravity(spec.gravity);
             s.sim->set_live_parameters(spec);
           })
      .def("save_checkpoint",
           [](PySimulation& s, const std::filesystem::path& path) {
             nb::gil_scoped_release release;
             Lock l(checked(s).mutex);
             app::save_checkpoint(path, *s.sim);
           },
           nb::arg("path"), "Writes the state and its scene (beside it), as `rtsph run` does.")
      .def("_read_checkpoint",
           [](PySimulation& s, const std::string& path) {
             nb::gil_scoped_release release;
             Lock l(checked(s).mutex);
             io::read_checkpoint(path, *s.sim, app::scene_hash(s.sim->spec()));
           })
      .def("_export", &export_frame, nb::arg("dir"), nb::arg("format"), nb::arg("attributes"))
      .def("close", [](PySimulation& s) { std::lock_guard<std::mutex> l(s.mutex.m); s.sim.reset(); s.exporters.clear(); },
           "Frees the engine's memory now; the object is unusable afterwards.");

  m.def("_checkpoint_scene", [](const std::string& path) {
    app::inspect_checkpoint(path);
    return PyScene{app::load_checkpoint_scene(path)};
  });
}

}  // namespace rtsph::py
