// checkpoint_file.cpp — named records with a version and a checksum; see
// checkpoint_file.hpp for the layout.
#include "cdyn/checkpoint_file.hpp"

#include <cstring>
#include <fstream>
#include <sstream>

#include "cdyn/atomic_file.hpp"
#include "cdyn/base/error.hpp"
#include "cdyn/checksum.hpp"

namespace cdyn {

namespace {

constexpr char kMagic[8] = {'C', 'D', 'Y', 'N', 'C', 'K', 'P', 'T'};
constexpr std::uint32_t kByteOrderMark = 0x01020304;

template <class T>
void put(std::string& out, const T& value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof value);
}

void put_record(std::string& out, char kind, const std::string& name, std::uint64_t count, const void* data,
                std::size_t bytes) {
  put(out, kind);
  put(out, static_cast<std::uint32_t>(name.size()));
  out += name;
  put(out, count);
  out.append(static_cast<const char*>(data), bytes);
}

// Reads the bytes of a checkpoint front to back; every overrun is a truncated file.
class Reader {
 public:
  Reader(std::string_view bytes, const std::filesystem::path& path) : bytes_(bytes), path_(path) {}

  template <class T>
  T get() {
    T value;
    std::memcpy(&value, take(sizeof value), sizeof value);
    return value;
  }
  // v = the next `count` values.  (No memcpy of none: an empty vector's data() may be
  // null, which memcpy's arguments must not be even for zero bytes.)
  template <class T>
  void into(std::vector<T>& v, std::uint64_t count) {
    v.resize(count);
    const char* from = take(count * sizeof(T));
    if (count > 0) std::memcpy(v.data(), from, count * sizeof(T));
  }
  const char* take(std::size_t n) {
    if (n > bytes_.size() - at_) fail("truncated (it ends inside a record)");
    const char* p = bytes_.data() + at_;
    at_ += n;
    return p;
  }
  std::size_t at() const { return at_; }
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(path_.string() + ": not a valid checkpoint: " + what);
  }

 private:
  std::string_view bytes_;
  const std::filesystem::path& path_;
  std::size_t at_ = 0;
};

}  // namespace

void write_checkpoint_file(const std::filesystem::path& path, const CheckpointRecords& r) {
  std::string out(kMagic, sizeof kMagic);
  put(out, kCheckpointVersion);
  put(out, kByteOrderMark);
  put(out, static_cast<std::uint64_t>(r.numbers.size() + r.integers.size() + r.texts.size()));
  for (const auto& [name, v] : r.numbers) put_record(out, 'd', name, v.size(), v.data(), v.size() * sizeof(double));
  for (const auto& [name, v] : r.integers)
    put_record(out, 'i', name, v.size(), v.data(), v.size() * sizeof(std::int64_t));
  for (const auto& [name, v] : r.texts) put_record(out, 's', name, v.size(), v.data(), v.size());
  put(out, fnv1a(out));
  write_file_atomically(path, out);
}

CheckpointRecords read_checkpoint_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string() + ": no checkpoint to resume from");
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string bytes = buffer.str();
  Reader read(bytes, path);
  if (bytes.size() < sizeof kMagic || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0)
    read.fail("it does not start with CDYNCKPT");
  read.take(sizeof kMagic);
  const auto version = read.get<std::uint32_t>();
  if (version != kCheckpointVersion)
    read.fail("format version " + std::to_string(version) + ", this cdyn reads version " +
              std::to_string(kCheckpointVersion));
  if (read.get<std::uint32_t>() != kByteOrderMark) read.fail("written on a machine of the other byte order");
  // The checksum covers everything before its own 8 bytes: check it before trusting a count.
  if (bytes.size() < read.at() + 8) read.fail("truncated");
  const std::size_t body = bytes.size() - sizeof(std::uint64_t);
  std::uint64_t stored;
  std::memcpy(&stored, bytes.data() + body, sizeof stored);
  if (fnv1a(std::string_view(bytes.data(), body)) != stored)
    read.fail("its checksum does not match (the file is corrupt or cut short)");

  CheckpointRecords r;
  const auto n = read.get<std::uint64_t>();
  for (std::uint64_t k = 0; k < n; ++k) {
    const char kind = read.get<char>();
    const auto length = read.get<std::uint32_t>();
    const std::string name(read.take(length), length);
    const auto count = read.get<std::uint64_t>();
    if (count > bytes.size()) read.fail("record '" + name + "' is longer than the file");
    if (kind == 'd') {
      read.into(r.numbers[name], count);
    } else if (kind == 'i') {
      read.into(r.integers[name], count);
    } else if (kind == 's') {
      r.texts[name] = std::string(read.take(count), count);
    } else {
      read.fail("record '" + name + "' has an unknown kind");
    }
  }
  if (read.at() != body) read.fail("bytes after the last record");
  return r;
}

}  // namespace cdyn
