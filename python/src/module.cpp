// rtsph._rtsph: the extension module. Exceptions map to Python's as the CLI maps them to exit
// codes: bad input (scene, checkpoint, arguments) is a ValueError, I/O an OSError.
#include <nanobind/nanobind.h>
#include <nanobind/stl/pair.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include "binding.h"
#include "io/errors.h"
#include "scene/scene.h"
#include "solvers/simulation.h"

namespace rtsph::py {

void bind_scene(nb::module_& m) {
  nb::class_<PyScene>(m, "_Scene")
      .def_prop_ro("name", [](const PyScene& s) { return s.spec.name; })
      .def_prop_ro("dimension", [](const PyScene& s) { return s.spec.dimension; })
      .def_prop_ro("method", [](const PyScene& s) { return s.spec.method; })
      .def_prop_ro("end_time", [](const PyScene& s) { return s.spec.end_time; })
      .def("to_json", [](const PyScene& s) { return scene_to_json(s.spec); },
           "Canonical JSON of the whole scene: every key, fixed order, exact numbers.")
      .def("_override",
           [](const PyScene& s, const std::string& assignment) {
             PyScene out{s.spec};
             apply_override(out.spec, assignment, "override");
             return out;
           },
           nb::arg("assignment"));

  m.def("_load_scene", [](const std::string& name_or_path) { return PyScene{load_scene(name_or_path)}; },
        nb::arg("name_or_path"));
  m.def("_parse_scene",
        [](const std::string& text, const std::string& source) { return PyScene{parse_scene(text, source)}; },
        nb::arg("text"), nb::arg("source"));
  m.def("_builtin_scenes", [] { return builtin_scenes(); });
  m.def("solver_methods", [] { return solver_methods(); }, "The registered solver method names.");
}

}  // namespace rtsph::py

NB_MODULE(_rtsph, m) {
  namespace nb = nanobind;
  using namespace rtsph;
  m.doc() = "rtsph engine (extension module; use the `rtsph` package)";
  // Most specific last: nanobind tries translators from the newest registration back.
  nb::exception<io::IoError>(m, "IoError", PyExc_OSError);
  nb::exception<io::CheckpointError>(m, "CheckpointError", PyExc_ValueError);
  nb::exception<SceneError>(m, "SceneError", PyExc_ValueError);
  nb::exception<py::InstabilityError>(m, "InstabilityError", PyExc_RuntimeError);
  py::bind_scene(m);
  py::bind_simulation(m);
  py::bind_render(m);
}
