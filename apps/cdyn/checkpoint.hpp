// checkpoint.hpp — the checkpoint of a run (`output.checkpoint_every`, `cdyn run
// --resume DIR`; docs/outputs.md, "Restart"): everything a run needs to go on from
// step n as if it had never stopped.
//
//   DIR/checkpoint/state.bin     the records below (io/cdyn/checkpoint_file.hpp: a
//                                version and a checksum; replaced atomically)
//   DIR/checkpoint/history.csv   the journal of history.csv's rows (io/cdyn/journal.hpp),
//   DIR/checkpoint/contact.csv   and of contact.csv's, trusted up to the marks in state.bin
//
// A run on subdomains (partition.hpp) writes one state file a rank, state.bin for rank 0
// and state.rankR.bin for rank R ≥ 1, each with the rank's share of the state and the
// list of its cells: a resumed run must deal the cells out as the stopped one did.
//
// The state (t, U, V, the last reaction), the scheme's memory (warm starts, U^{n−1},
// ..., schemes/scheme_memory.hpp), the totals and monitors of summary.json, the
// displacement rate of the last step, the field files written, and the fingerprint of
// DIR/scene.toml: a checkpoint is refused for another scene.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "cdyn/schemes/time_scheme.hpp"
#include "run_history.hpp"
#include "run_report.hpp"

namespace cdyn::app {

struct RunCheckpoint {
  std::string scene_hash;  // fnv1a of scene.toml, in hex (checksum.hpp)
  int step = 0;
  State state;
  SchemeMemory scheme;
  Energy E_initial;
  double drift_abs = 0.0, drift_half_sum = 0.0;  // EnergyDrift's state
  RunTotals totals;
  HistoryMemory history;
  Eigen::VectorXd rate;                          // (Uⁿ − Uⁿ⁻¹)/dt on all dofs of W^h
  std::vector<std::pair<int, double>> frames;    // the field files written: step, t
  std::vector<int> cells;                        // on subdomains: the rank's cells (empty otherwise)
};

// The folder of the checkpoint in a run directory.
inline std::filesystem::path checkpoint_dir(const std::filesystem::path& out) { return out / "checkpoint"; }

// The state file of rank `rank` of a run (0 for a serial run).
std::filesystem::path checkpoint_file(const std::filesystem::path& out, int rank = 0);

// Writes c as the checkpoint of the run in `out`, rank `rank`'s file (its journals must
// have been flushed: History::checkpoint()).
void write_checkpoint(const std::filesystem::path& out, const RunCheckpoint& c, int rank = 0);

// The checkpoint of the run in `out` (rank `rank`'s file), for the scene whose scene.toml
// text is `scene_text`.  InputError naming the file: none, corrupt, another version, or
// written for another scene.
RunCheckpoint read_checkpoint(const std::filesystem::path& out, const std::string& scene_text, int rank = 0);

// The fingerprint of a scene.toml text.
std::string scene_fingerprint(const std::string& scene_text);

}  // namespace cdyn::app
