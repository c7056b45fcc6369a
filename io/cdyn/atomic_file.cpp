// atomic_file.cpp — write to a temporary name in the target's directory, then rename
// (see atomic_file.hpp for why).
#include "cdyn/atomic_file.hpp"

#include <unistd.h>

#include <atomic>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include "cdyn/base/error.hpp"

namespace cdyn {

namespace {

constexpr std::string_view kMarker = ".tmp-";

// ".<name>.tmp-<pid>-<k>": the pid separates concurrent processes writing the same
// directory, k the AtomicFiles of one process (even of the same target).
std::filesystem::path temporary_for(const std::filesystem::path& target) {
  static std::atomic<unsigned long> counter{0};
  std::string name(1, '.');  // appended piece by piece (GCC 12 warns, wrongly, on "." + s)
  name += target.filename().string();
  name += kMarker;
  name += std::to_string(::getpid());
  name += '-';
  name += std::to_string(counter++);
  return target.parent_path() / name;
}

}  // namespace

AtomicFile::AtomicFile(std::filesystem::path target) : target_(std::move(target)), temporary_(temporary_for(target_)) {
  if (target_.filename().empty()) throw InputError(target_.string() + ": not a file name");
  os_.open(temporary_, std::ios::binary | std::ios::trunc);
  if (!os_) throw InputError(target_.string() + ": cannot create the file (is its directory there and writable?)");
}

AtomicFile::~AtomicFile() {
  if (committed_) return;
  os_.close();
  std::error_code ec;  // a destructor must not throw
  std::filesystem::remove(temporary_, ec);
}

void AtomicFile::commit() {
  if (committed_) throw std::logic_error("AtomicFile::commit called twice for " + target_.string());
  os_.flush();
  const bool written = static_cast<bool>(os_);
  os_.close();
  std::error_code ec;
  if (!written || os_.fail()) {
    std::filesystem::remove(temporary_, ec);
    throw InputError(target_.string() + ": cannot write (disk full or file system error)");
  }
  std::filesystem::rename(temporary_, target_, ec);
  if (ec) {
    std::error_code ignored;
    std::filesystem::remove(temporary_, ignored);
    throw InputError(target_.string() + ": cannot rename the finished file into place (" + ec.message() + ")");
  }
  committed_ = true;
}

void write_file_atomically(const std::filesystem::path& path, std::string_view content) {
  AtomicFile f(path);
  f.stream().write(content.data(), static_cast<std::streamsize>(content.size()));
  f.commit();
}

bool is_atomic_temporary(const std::filesystem::path& file) {
  const std::string name = file.filename().string();
  const auto marker = name.rfind(kMarker);
  if (name.size() < 2 || name[0] != '.' || marker == std::string::npos || marker < 2) return false;
  // after the marker: <digits>-<digits>
  const std::string rest = name.substr(marker + kMarker.size());
  const auto dash = rest.find('-');
  auto digits = [](const std::string& s) {
    return !s.empty() && s.find_first_not_of("0123456789") == std::string::npos;
  };
  return dash != std::string::npos && digits(rest.substr(0, dash)) && digits(rest.substr(dash + 1));
}

int remove_stale_temporaries(const std::filesystem::path& directory) {
  std::error_code ec;
  if (!std::filesystem::is_directory(directory, ec)) return 0;
  std::vector<std::filesystem::path> stale;
  for (const auto& entry : std::filesystem::directory_iterator(directory, ec))
    if (is_atomic_temporary(entry.path())) stale.push_back(entry.path());
  int removed = 0;
  for (const auto& path : stale) removed += std::filesystem::remove(path, ec) ? 1 : 0;
  return removed;
}

}  // namespace cdyn
