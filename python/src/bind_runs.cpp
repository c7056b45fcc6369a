// bind_runs.cpp — the command line's commands in Python, by the command line's own code
// (apps/cdyn, library cdyn_frontend): `cdyn run`, `cdyn study` and `cdyn wellposed` on a
// scene (a file, the embedded default, or TOML text made from a Python dict) with --set
// overrides, and the Simulation a scene builds — mesh, problem, solver, scheme and
// initial state, exactly what `cdyn run` integrates — for stepping by hand.
//
// The commands run without the GIL (the scene's data are muParser expressions, no Python
// is called); their files are read back by cdyn/runs.py.  Ctrl-C stops a run or a study
// as on the command line (exit status 130, results marked partial).
#include <memory>

#include "cdyn/base/error.hpp"
#include "cdyn_python.hpp"
#include "commands.hpp"
#include "diagnostics.hpp"
#include "scene.hpp"
#include "simulation.hpp"

namespace cdyn::python {

namespace {

// The scene as a command sees it: the file (or text) with the --set overrides applied,
// values naming files made relative to the current directory as on the command line.
app::Scene command_scene(const std::string& path, const std::string& text, const std::vector<std::string>& sets) {
  app::Scene scene = app::Scene::load(path, text);
  for (const std::string& a : app::command_line_paths(sets)) scene.set(a);
  return scene;
}

py::object from_json(const nlohmann::ordered_json& j) { return py::module_::import("json").attr("loads")(j.dump()); }

}  // namespace

void bind_runs(py::module_& m) {
  m.def(
      "_run_command",
      [](const std::string& scene, const std::string& text, const std::vector<std::string>& sets,
         const std::string& out) {
        app::RunOptions o;
        o.scene = scene;
        o.scene_text = text;
        o.sets = sets;
        o.out = out;
        o.quiet = true;     // the results are returned instead of the final paragraph
        o.warnings = false;  // cdyn/runs.py turns summary.json's warnings into Python warnings
        return app::cmd_run(o);
      },
      "scene"_a, "text"_a, "sets"_a, "out"_a, py::call_guard<py::gil_scoped_release>(),
      "`cdyn run SCENE --set ... --out OUT --quiet`; returns the exit status (0, or 130 when interrupted)");
  m.def(
      "_study_command",
      [](const std::string& scene, const std::string& text, const std::vector<std::string>& varies,
         const std::vector<std::string>& sets, const std::string& out, const std::string& error, bool fields) {
        app::StudyOptions o;
        o.scene = scene;
        o.scene_text = text;
        o.varies = varies;
        o.sets = sets;
        o.out = out;
        o.error = error;
        o.fields = fields;
        return app::cmd_study(o);
      },
      "scene"_a, "text"_a, "varies"_a, "sets"_a, "out"_a, "error"_a, "fields"_a,
      py::call_guard<py::gil_scoped_release>(), "`cdyn study`; returns the exit status");
  m.def(
      "_wellposed_rows",
      [](const std::string& scene, const std::string& text, const std::vector<std::string>& sets) {
        nlohmann::ordered_json rows;
        {
          py::gil_scoped_release release;
          rows = app::wellposed_rows(app::make_simulation(command_scene(scene, text, sets)));
        }
        return from_json(rows);
      },
      "scene"_a, "text"_a, "sets"_a, "the rows of `cdyn wellposed --json`");
  m.def(
      "_scene_name",
      [](const std::string& scene, const std::string& text, const std::vector<std::string>& sets) {
        return command_scene(scene, text, sets).name();
      },
      "scene"_a, "text"_a, "sets"_a);
  m.def(
      "_scene_text",
      [](const std::string& scene, const std::string& text, const std::vector<std::string>& sets) {
        return command_scene(scene, text, sets).dump();
      },
      "scene"_a, "text"_a, "sets"_a);
  m.def("default_scene", &app::default_scene_text, "the embedded default scene (the seed's membrane), TOML text");

  py::class_<app::Simulation, std::unique_ptr<app::Simulation>>(
      m, "Simulation", "What `cdyn run` integrates: the scene's mesh, problem, solver, scheme and initial state")
      .def_readonly("name", &app::Simulation::scene_name)
      .def_readonly("model", &app::Simulation::model)
      .def_readonly("pair", &app::Simulation::pair)
      .def_readonly("scheme_name", &app::Simulation::scheme_name)
      .def_readonly("solver_name", &app::Simulation::solver_name)
      .def_readonly("dt", &app::Simulation::dt)
      .def_readonly("T", &app::Simulation::T)
      .def_readonly("n_steps", &app::Simulation::n_steps)
      .def_readonly("output_every", &app::Simulation::output_every)
      .def_property_readonly("mesh", [](const app::Simulation& s) -> const Mesh& { return *s.mesh; },
                             py::return_value_policy::reference_internal)
      .def_readonly("problem", &app::Simulation::problem)
      .def_property_readonly("solver", [](app::Simulation& s) -> StepSolver& { return *s.solver; },
                             py::return_value_policy::reference_internal)
      .def_property_readonly("scheme", [](app::Simulation& s) -> TimeScheme& { return *s.scheme; },
                             py::return_value_policy::reference_internal)
      .def_property_readonly(
          "initial", [](const app::Simulation& s) { return State(s.initial); },
          "the initial state (a copy, already initialized for the scheme, as `cdyn run` starts from)")
      .def_property_readonly(
          "probes",
          [](const app::Simulation& s) {
            py::dict out;
            for (const app::Probe& p : s.probes)
              out[py::str(p.name)] = py::dict("point"_a = py::make_tuple(p.at.x, p.at.y, p.at.z), "cell"_a = p.where.cell,
                                              "xi"_a = p.where.xi, "vertex"_a = p.vertex);
            return out;
          },
          "name → point, the cell and reference point holding it, the nearest vertex")
      .def_property_readonly("warnings", &app::run_warnings)
      .def_property_readonly(
          "wellposed", [](const app::Simulation& s) { return from_json(app::wellposedness_summary(s)); },
          "summary.json's wellposed entry for the scene's pair");
  m.def(
      "_simulation",
      [](const std::string& scene, const std::string& text, const std::vector<std::string>& sets) {
        // Built in place (no move): the scheme refers to the simulation's own problem and solver.
        return std::unique_ptr<app::Simulation>(new app::Simulation(app::make_simulation(command_scene(scene, text, sets))));
      },
      "scene"_a, "text"_a, "sets"_a);
}

}  // namespace cdyn::python
