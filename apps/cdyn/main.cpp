// main.cpp — the `cdyn` command line (README.md, "Command line").
//
// Parses the subcommand with CLI11 and hands over to commands.hpp.  The exit status
// contract: 0 success, 2 bad input (one line on stderr naming the key or file),
// 3 numerical failure (reported, never silently continued).
//
// Under `mpirun -n P` (P > 1) rank 0 runs the command and the other ranks serve the
// distributed step solves of the PETSc back end (qp/petsc/backend.hpp,
// docs/distributed.md); only rank 0 reads the scene, writes and reports.  A run on
// subdomains (solver.partition) is run by every rank, each on its own cells; rank 0
// alone writes and reports.
#include <CLI/CLI.hpp>
#include <iostream>
#ifdef __GLIBC__
#include <malloc.h>
#endif

#include "cdyn/base/error.hpp"
#include "cdyn/version.hpp"
#include "cdyn/qp/petsc/backend.hpp"
#include "commands.hpp"

namespace {

// Every block from the heap, and the heap never trimmed: a freed block is reused by the
// next allocation instead of being given back to the system.  glibc serves a block of
// more than 32 MB (a sparse matrix of a large mesh, its transpose, a product, the
// triplets of an assembly) by a fresh mmap, whose every page then faults on its first
// write, and unmaps it on free.  Measured on the 32³ cube (697 635 unknowns, P1+/P0):
// set-up 19.7 → 7.7 s, the first step 3.4 → 1.1 s, peak memory 1.54 → 1.58 GB
// (docs/performance.md, "Set-up").  The process's memory stays at its peak until it
// exits, which a run reaches anyway; the Python module leaves its interpreter's
// allocator alone.
void keep_freed_memory() {
#ifdef __GLIBC__
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_TRIM_THRESHOLD, -1);
#endif
}

// How long a rank that failed waits for the others to fail too (a run on subdomains).
constexpr double kWaitForTheOtherRanks = 10.0;

}  // namespace

int main(int argc, char** argv) {
  keep_freed_memory();
  CLI::App app{"cdyn — a reference kernel for dynamic contact and constrained wave problems"};
  app.set_version_flag("--version", std::string("cdyn ") + cdyn::version);
  app.require_subcommand(1);

  cdyn::app::RunOptions run_options;
  auto* run = app.add_subcommand("run", "Integrate a scene in time (no scene: the seed's membrane experiment)");
  run->add_option("SCENE", run_options.scene, "a scene file (.toml)");
  run->add_option("--out", run_options.out, "output directory (default out/<scene name>)");
  run->add_option("--set", run_options.sets, "override a scene key, e.g. --set time.dt=0.002")->allow_extra_args(false);
  run->add_flag("--quiet", run_options.quiet, "no progress line and no final summary");
  run->add_option("--resume", run_options.resume,
                  "continue the run in DIR from its last checkpoint (output.checkpoint_every; its scene is "
                  "DIR/scene.toml)");

  cdyn::app::WellposedOptions wp_options;
  auto* wellposed = app.add_subcommand("wellposed", "Condition (12) for every pair on a scene's mesh and constraints");
  wellposed->add_option("SCENE", wp_options.scene, "a scene file (.toml); none: the default scene");
  wellposed->add_option("--set", wp_options.sets, "override a scene key")->allow_extra_args(false);
  wellposed->add_flag("--json", wp_options.json, "print the table as JSON");

  cdyn::app::StudyOptions study_options;
  auto* study = app.add_subcommand("study", "Run every combination of --vary values; study.csv and a work-precision plot");
  study->add_option("SCENE", study_options.scene, "a scene file (.toml); none: the default scene");
  study->add_option("--vary", study_options.varies, "a key and its values, e.g. --vary time.dt=0.004,0.002,0.001")
      ->required()
      ->allow_extra_args(false);
  study->add_option("--out", study_options.out, "output directory (default out/<scene name>-study)");
  study->add_option("--set", study_options.sets, "override a scene key in every run")->allow_extra_args(false);
  study->add_option("--error", study_options.error,
                    "the error of a run: auto (default), exact, energy or probe:NAME[:COLUMN] against the finest run");
  study->add_flag("--fields", study_options.fields, "the runs write their field files (off by default)");

  std::string mesh_file;
  auto* mesh = app.add_subcommand("mesh", "Summarise a mesh (.geo or .msh) and its physical groups");
  mesh->add_option("FILE", mesh_file, "a gmsh .geo or .msh (2.2 or 4.1) file")->required();
  std::vector<std::string> mesh_sets;
  mesh->add_option("--set", mesh_sets, "a .geo parameter, e.g. --set h=0.5 (as gmsh -setnumber h 0.5)")
      ->allow_extra_args(false);

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    std::cout << e.what() << "\n";
    return 0;
  } catch (const CLI::ParseError& e) {
    std::cerr << "cdyn: error: " << e.what() << " (see cdyn --help)\n";
    return 2;
  }

  if (cdyn::petsc::launched_in_parallel()) {
    try {
      cdyn::petsc::initialize();
    } catch (const cdyn::InputError& e) {
      std::cerr << "cdyn: error: " << e.what() << "\n";
      return 2;
    }
    if (*run && cdyn::app::runs_on_subdomains(run_options)) {
      cdyn::petsc::every_rank_runs();
      run_options.every_rank = true;
    }
    else if (cdyn::petsc::rank() != 0)
      return cdyn::petsc::end_process(cdyn::petsc::serve());
  }
  std::string failure;  // the one line of a failed command
  auto command = [&]() -> int {
    try {
      if (*run) return cdyn::app::cmd_run(run_options);
      if (*study) return cdyn::app::cmd_study(study_options);
      if (*wellposed) {
        wp_options.sets = cdyn::app::command_line_paths(wp_options.sets);
        return cdyn::app::cmd_wellposed(wp_options);
      }
      if (*mesh) return cdyn::app::cmd_mesh(mesh_file, mesh_sets);
    } catch (const cdyn::InputError& e) {
      failure = std::string("cdyn: error: ") + e.what();
      return 2;
    } catch (const cdyn::NumericalError& e) {
      failure = std::string("cdyn: numerical failure: ") + e.what();
      return 3;
    }
    return 0;
  };
  const int status = command();
  // On subdomains every rank meets the same error (the same scene, the checks agreed on
  // before a collective call), and rank 0 says it.  A rank that failed alone (say, a
  // mesh file its machine cannot read) would leave the others waiting for it in their
  // next collective call: it waits for them a while, then says why and ends the job.
  const bool failed_here = !failure.empty();
  // (each line one write: mpirun forwards a process's stderr as it comes, and its own
  // notice of the abort came between two pieces of the line under load)
  if (run_options.every_rank && failed_here && !cdyn::petsc::ranks_meet(kWaitForTheOtherRanks)) {
    std::cerr << failure + " (rank " + std::to_string(cdyn::petsc::rank()) +
                     "; the other ranks did not stop with it: the job is ended)\n";
    cdyn::petsc::abort_all(status);
  }
  if (failed_here && cdyn::petsc::rank() == 0) std::cerr << failure + "\n";
  // (rank 0 tells the other ranks to quit, if any, and PETSc ends, if it was started)
  return cdyn::petsc::end_process(status);
}
