// csv_output.cpp — a run's CSV file and its journal; see csv_output.hpp.
#include "csv_output.hpp"

namespace cdyn::app {

CsvOutput::CsvOutput(const std::filesystem::path& target, const std::filesystem::path& journal,
                     const std::optional<JournalMark>& resume)
    : resumed_(resume.has_value()) {
  rows_.precision(17);
  if (target.empty()) return;
  file_.emplace(target);
  if (journal.empty()) return;
  if (!resume) {
    journal_.emplace(journal);
    return;
  }
  std::string kept;
  journal_.emplace(journal, *resume, &kept);
  file_->stream() << kept;
}

void CsvOutput::end_rows() {
  const std::string_view text = rows_.view();
  if (file_) file_->stream() << text;
  if (journal_) unjournaled_ += text;
  rows_.str("");
}

JournalMark CsvOutput::checkpoint() {
  if (!journal_) return {};  // (a rank that writes no file)
  journal_->append(unjournaled_);
  unjournaled_.clear();
  return journal_->flush();
}

}  // namespace cdyn::app
