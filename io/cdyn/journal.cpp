// journal.cpp — appends, marks, and the journal taken back at a mark; see journal.hpp.
#include "cdyn/journal.hpp"

#include <sstream>

#include "cdyn/base/error.hpp"

namespace cdyn {

Journal::Journal(std::filesystem::path path) : path_(std::move(path)) {
  os_.open(path_, std::ios::binary | std::ios::trunc);
  if (!os_) throw InputError(path_.string() + ": cannot create the file");
}

Journal::Journal(std::filesystem::path path, const JournalMark& mark, std::string* kept) : path_(std::move(path)) {
  std::ifstream in(path_, std::ios::binary);
  if (!in) throw InputError(path_.string() + ": missing (the checkpoint's rows are in it)");
  std::stringstream buffer;
  buffer << in.rdbuf();
  std::string bytes = buffer.str();
  in.close();
  if (bytes.size() < mark.length)
    throw InputError(path_.string() + ": shorter (" + std::to_string(bytes.size()) + " bytes) than its checkpoint says (" +
                     std::to_string(mark.length) + ")");
  bytes.resize(mark.length);
  if (fnv1a(bytes) != mark.hash)
    throw InputError(path_.string() + ": does not match its checkpoint (the file is corrupt)");
  std::error_code ec;
  std::filesystem::resize_file(path_, mark.length, ec);  // the rows of steps after the checkpoint
  if (ec) throw InputError(path_.string() + ": cannot cut it at its checkpoint (" + ec.message() + ")");
  os_.open(path_, std::ios::binary | std::ios::app);
  if (!os_) throw InputError(path_.string() + ": cannot open it for appending");
  mark_ = mark;
  if (kept) *kept = std::move(bytes);
}

void Journal::append(std::string_view text) {
  os_.write(text.data(), static_cast<std::streamsize>(text.size()));
  mark_.length += text.size();
  mark_.hash = fnv1a(text, mark_.hash);
}

JournalMark Journal::flush() {
  os_.flush();
  if (!os_) throw InputError(path_.string() + ": write failed (disk full?)");
  return mark_;
}

}  // namespace cdyn
