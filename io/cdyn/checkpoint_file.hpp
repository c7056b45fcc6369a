// checkpoint_file.hpp — the file of a checkpoint: named arrays of numbers and texts,
// with a format version and a checksum (docs/outputs.md, "Restart").
//
// Layout, every integer in the byte order of the machine that wrote it:
//     "CDYNCKPT"                      8 bytes, the magic
//     version                         u32 (kCheckpointVersion)
//     byte-order mark 0x01020304      u32 (read back otherwise on a machine of the other order)
//     number of records               u64
//     per record, sorted by name:
//       kind                          u8: 'd' doubles, 'i' 64-bit integers, 's' bytes
//       name length, name             u32, bytes
//       count, payload                u64 (values, or bytes for 's'), 8 bytes a value
//     FNV-1a 64 of every byte above   u64 (checksum.hpp)
// Doubles are stored as their bytes, so they come back bit for bit.  Written under a
// temporary name and renamed (atomic_file.hpp): a checkpoint is the old one or the new
// one, never half of either.  What the records mean is the command line's business.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace cdyn {

// 2 since history.csv has a reconstruction_s column and the run totals its cost: the
// rows and totals a version 1 checkpoint takes back do not match what this cdyn writes.
constexpr std::uint32_t kCheckpointVersion = 2;

struct CheckpointRecords {
  std::map<std::string, std::vector<double>> numbers;
  std::map<std::string, std::vector<std::int64_t>> integers;
  std::map<std::string, std::string> texts;
};

// Writes the records to `path` atomically.  InputError naming the path if it cannot.
void write_checkpoint_file(const std::filesystem::path& path, const CheckpointRecords& records);

// Reads them back.  InputError naming the path for a missing file, another magic or
// version, the other byte order, a truncated file, a checksum that does not match.
CheckpointRecords read_checkpoint_file(const std::filesystem::path& path);

}  // namespace cdyn
