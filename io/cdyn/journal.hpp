// journal.hpp — a text file that grows by appends and is trusted up to a mark (a
// length and the hash of the bytes up to it) kept elsewhere: the rows of history.csv
// and contact.csv that a checkpoint covers (docs/outputs.md, "Restart").
//
// A run appends the rows of the steps since the last checkpoint, flushes them, and only
// then writes the checkpoint that records the journal's new mark.  A run killed in
// between leaves rows beyond the mark (or half a row): whoever resumes from the
// checkpoint takes the journal back at its mark, checks the hash of what precedes it
// and cuts the rest off.  So the file needs no atomic rename, and a run writes each row
// once however many checkpoints it makes.  (No fsync, as for atomic_file.hpp: the
// guarantee is against a killed process, not a power failure.)
#pragma once

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "cdyn/checksum.hpp"

namespace cdyn {

struct JournalMark {
  std::uint64_t length = 0;
  std::uint64_t hash = kFnv1aOffset;  // fnv1a of the first `length` bytes
};

class Journal {
 public:
  // A new, empty journal at `path` (an existing file is replaced).  InputError naming
  // the path if it cannot be created.
  explicit Journal(std::filesystem::path path);
  // The journal at `path` taken back at `mark`: its first mark.length bytes, which must
  // hash to mark.hash, are kept (and given in *kept), the rest cut off.  InputError
  // naming the path for a missing file, a shorter one, or a hash that does not match.
  Journal(std::filesystem::path path, const JournalMark& mark, std::string* kept);

  void append(std::string_view text);
  // Hands the appended bytes to the operating system and returns the mark of all of
  // them.  InputError naming the path if a write failed (a full disk).
  JournalMark flush();

  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  std::ofstream os_;
  JournalMark mark_;
};

}  // namespace cdyn
