// atomic_file.hpp — output files that appear complete or not at all.
//
// A run can be interrupted (Ctrl-C, a kill, a crash, a full disk) while it writes.  A
// file written in place would then be left truncated under its final name, looking
// like a result.  An AtomicFile writes to a temporary name in the SAME directory
// (".<name>.tmp-<pid>-<k>", hidden, so ParaView's series globbing ignores it) and
// commit() closes it and renames it to the final name with std::filesystem::rename,
// which POSIX rename(2) makes atomic within one file system: a reader sees the old
// file or the new one, never a part.  A file that is never committed (exception,
// early return) is removed by the destructor; one left behind by a killed process
// keeps its hidden temporary name (remove_stale_temporaries() clears them).
//
// No fsync: the guarantee is against an interrupted process, not a power failure.
#pragma once

#include <filesystem>
#include <fstream>
#include <string_view>

namespace cdyn {

class AtomicFile {
 public:
  // Opens the temporary file for `target` (binary mode).  Throws InputError naming
  // `target` when its directory does not exist or the file cannot be created.
  explicit AtomicFile(std::filesystem::path target);
  ~AtomicFile();  // not committed: closes and removes the temporary
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ostream& stream() { return os_; }
  const std::filesystem::path& target() const { return target_; }
  const std::filesystem::path& temporary() const { return temporary_; }
  bool committed() const { return committed_; }

  // Flushes and closes the temporary, then renames it to the target (replacing an
  // existing file).  Throws InputError naming the target if any write failed or the
  // rename fails; the temporary is removed then.  Calling it twice is an error
  // (std::logic_error).
  void commit();

 private:
  std::filesystem::path target_, temporary_;
  std::ofstream os_;
  bool committed_ = false;
};

// Writes `content` to `path` atomically (an AtomicFile written in one go).
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

// The temporary name AtomicFile uses for `target` in this process (for tests and for
// remove_stale_temporaries).
bool is_atomic_temporary(const std::filesystem::path& file);

// Removes the temporaries of AtomicFiles left in `directory` by interrupted
// processes (names ".<name>.tmp-<pid>-<k>").  Returns how many were removed.
int remove_stale_temporaries(const std::filesystem::path& directory);

}  // namespace cdyn
