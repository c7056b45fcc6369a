// commands.hpp — the subcommands of the `cdyn` command line (one file each).
// Each returns the process exit status; bad input is thrown as cdyn::InputError and
// turned into one line and exit status 2 by main(), numerical failure as
// cdyn::NumericalError (exit status 3).
#pragma once

#include <nlohmann/json.hpp>

#include "cdyn/wellposedness/condition12.hpp"
#include <string>
#include <vector>

namespace cdyn::app {

struct Simulation;

// `cdyn mesh FILE.geo|FILE.msh [--set name=value]...`: counts, measure, h and the
// physical groups; --set gives a .geo parameter (gmsh -setnumber, a scene's mesh.set).
int cmd_mesh(const std::string& file, const std::vector<std::string>& sets = {});

// `cdyn run [SCENE.toml] [--out DIR] [--set key=value]... [--quiet]`, or
// `cdyn run --resume DIR [--quiet]`: the run in DIR from its last checkpoint.
struct RunOptions {
  std::string scene;               // empty: the embedded default scene
  std::string out;                 // empty: out/<scene name>
  std::vector<std::string> sets;   // key=value overrides
  bool quiet = false;
  bool warnings = true;            // print the run's warnings on stderr (cdyn study prints its own)
  std::string scene_text;          // not empty: the scene itself as TOML text, `scene` its source's name
  std::string resume;              // a run directory to resume (then no scene, sets or out)
  bool every_rank = false;         // on subdomains: every rank of mpirun runs the command (main.cpp)
};
int cmd_run(const RunOptions& options);

// Whether the scene of these options asks for a run on subdomains (solver.partition),
// which every rank of mpirun runs; false also when the scene cannot be read (the run
// then reports why, from rank 0).
bool runs_on_subdomains(const RunOptions& options);

// --set values that name files (mesh.file) are relative to the current directory, as
// one typing them expects, not to the scene file's directory as in the scene file:
// makes them absolute.  Applied by every command that takes --set.
std::vector<std::string> command_line_paths(std::vector<std::string> sets);

// `cdyn study [SCENE.toml] --vary key=v1,v2,... [--vary ...] [--out DIR] [--set ...]
// [--error MEASURE] [--fields]`: one run per combination of the varied values, then
// study.csv and the work-precision plot (docs/outputs.md).
struct StudyOptions {
  std::string scene;
  std::string out;                 // empty: out/<scene name>-study
  std::vector<std::string> varies; // key=v1,v2,...
  std::vector<std::string> sets;   // applied to every run, before the varied values
  std::string error = "auto";      // the error measure (study_error.hpp)
  bool fields = false;             // the runs write their field files
  std::string scene_text;          // as RunOptions::scene_text
};
int cmd_study(const StudyOptions& options);

// `cdyn wellposed [SCENE.toml] [--set key=value]... [--json]`: condition (12) for
// every pair on the scene's mesh and constraints.
struct WellposedOptions {
  std::string scene;
  std::vector<std::string> sets;
  bool json = false;
  std::string scene_text;          // as RunOptions::scene_text
};
int cmd_wellposed(const WellposedOptions& options);

// The rows of `cdyn wellposed --json`: condition (12) on the simulation's mesh and
// constraints for every pair and classical mass model.
nlohmann::ordered_json wellposed_rows(const Simulation& sim);

// The setup of condition (12) for a simulation: its Dirichlet parts, constrained
// vertices and, for elasticity, two components and the plane's normal.  InputError
// when the check does not apply (rollers: wellposedness/condition12.hpp fixes whole vertices).
WellPosednessSetup wellposedness_setup(const Simulation& sim);

// Condition (12) for a simulation's pair and constraints, as summary.json's
// "wellposed" entry ({"beta", "satisfied"}, or why it was not computed), and as a
// phrase for the final paragraph.
nlohmann::ordered_json wellposedness_summary(const Simulation& sim);
std::string wellposedness_line(const nlohmann::ordered_json& entry);

}  // namespace cdyn::app
