// csv_output.hpp — a CSV file of a run (history.csv, contact.csv): written under a
// temporary name and renamed when the run ends (atomic_file.hpp), and, when the run
// makes checkpoints, its rows also appended to a journal at each checkpoint
// (journal.hpp), from which a resumed run takes them back (docs/outputs.md, "Restart").
#pragma once

#include <filesystem>
#include <optional>
#include <sstream>
#include <string>

#include "cdyn/atomic_file.hpp"
#include "cdyn/journal.hpp"

namespace cdyn::app {

class CsvOutput {
 public:
  // A new file (`journal` empty: no checkpoints), or with `resume` the file of a resumed
  // run, starting with the rows (header included) of the journal taken back at that mark.
  // `target` empty: no file (a rank of a run on subdomains other than the first, whose
  // records only take part in the sums).
  CsvOutput(const std::filesystem::path& target, const std::filesystem::path& journal,
            const std::optional<JournalMark>& resume = {});

  // Whether it starts with the rows of a resumed run (then the header is written).
  bool resumed() const { return resumed_; }
  // Where the rows are written (17 significant digits); end_rows() after each record.
  std::ostream& rows() { return rows_; }
  void end_rows();
  // Appends the rows since the last checkpoint to the journal: its mark for the checkpoint.
  JournalMark checkpoint();
  // Gives the file its name.
  void commit() {
    if (file_) file_->commit();
  }

 private:
  std::optional<AtomicFile> file_;
  std::optional<Journal> journal_;
  std::ostringstream rows_;
  std::string unjournaled_;  // the rows since the last checkpoint
  bool resumed_ = false;
};

}  // namespace cdyn::app
