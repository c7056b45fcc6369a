// test_checkpoint_file.cpp — io/cdyn/checkpoint_file and io/cdyn/journal: what a
// restart reads back is what was written, bit for bit, or it is refused naming the file.
//  - records of every kind come back equal (doubles with ==, NaN, −0 and denormals
//    included);
//  - a flipped byte anywhere, a file cut short, another version are refused;
//  - a journal taken back at a mark keeps its bytes up to the mark and cuts the rest; a
//    changed byte before the mark, or a file shorter than the mark, is refused.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

#include "cdyn/base/error.hpp"
#include "cdyn/checkpoint_file.hpp"
#include "cdyn/journal.hpp"

using namespace cdyn;
namespace fs = std::filesystem;

namespace {

// The test's scratch folder, removed when the test process ends (ctest runs each test
// in a process of its own).
const fs::path& scratch_dir() {
  static const struct Dir {
    fs::path path = fs::temp_directory_path() / ("cdyn_test_checkpoint_" + std::to_string(::getpid()));
    Dir() { fs::create_directories(path); }
    ~Dir() {
      std::error_code ec;
      fs::remove_all(path, ec);
    }
  } dir;
  return dir.path;
}

fs::path scratch(const std::string& name) { return scratch_dir() / name; }

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void write(const fs::path& p, const std::string& bytes) {
  std::ofstream(p, std::ios::binary | std::ios::trunc) << bytes;
}

CheckpointRecords sample() {
  CheckpointRecords r;
  r.numbers["U"] = {1.0 / 3.0, -0.0, std::numeric_limits<double>::denorm_min(), 1e308, std::nan("")};
  r.numbers["empty"] = {};
  r.integers["active"] = {0, -1, std::numeric_limits<std::int64_t>::max()};
  r.texts["scene"] = std::string("name = \"x\"\n\0binary", 18);
  return r;
}

}  // namespace

TEST(CheckpointFile, RoundTripIsBitForBit) {
  const fs::path p = scratch("round_trip.bin");
  const CheckpointRecords r = sample();
  write_checkpoint_file(p, r);
  const CheckpointRecords back = read_checkpoint_file(p);
  ASSERT_EQ(back.numbers.size(), 2u);
  const std::vector<double>& U = back.numbers.at("U");
  ASSERT_EQ(U.size(), 5u);
  for (std::size_t k = 0; k < U.size(); ++k)
    EXPECT_EQ(std::memcmp(&U[k], &r.numbers.at("U")[k], sizeof(double)), 0) << k;
  EXPECT_TRUE(back.numbers.at("empty").empty());
  EXPECT_EQ(back.integers, r.integers);
  EXPECT_EQ(back.texts, r.texts);
}

TEST(CheckpointFile, CorruptionIsRefused) {
  const fs::path p = scratch("corrupt.bin");
  write_checkpoint_file(p, sample());
  const std::string good = read(p);
  auto refused = [&](const std::string& bytes, const std::string& what) {
    write(p, bytes);
    try {
      read_checkpoint_file(p);
      ADD_FAILURE() << what << ": accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(p.string()), std::string::npos) << e.what();
    }
  };
  for (std::size_t at = 0; at < good.size(); at += 7) {
    std::string bad = good;
    bad[at] = static_cast<char>(bad[at] ^ 0x20);
    refused(bad, "byte " + std::to_string(at) + " flipped");
  }
  for (std::size_t n : {std::size_t(0), std::size_t(5), std::size_t(20), good.size() - 1})
    refused(good.substr(0, n), "cut at " + std::to_string(n));
  std::string other = good;
  // Byte 8 is the version's low byte on little-endian machines (on others its high byte:
  // still another version than this cdyn's).
  other[8] = static_cast<char>(kCheckpointVersion + 1);
  refused(other, "a later version");
  other[8] = 1;  // version 1: before history.csv's reconstruction_s column
  refused(other, "version 1");
  EXPECT_THROW(read_checkpoint_file(scratch("missing.bin")), InputError);
}

TEST(Journal, TakenBackAtItsMark) {
  const fs::path p = scratch("journal.csv");
  JournalMark mark;
  {
    Journal j(p);
    j.append("step,t\n0,0\n");
    j.append("1,0.1\n");
    mark = j.flush();
    j.append("2,0.2\n3,0.");  // after the checkpoint, cut short by a kill
    j.flush();
  }
  EXPECT_EQ(mark.length, 17u);
  std::string kept;
  {
    Journal j(p, mark, &kept);
    EXPECT_EQ(kept, "step,t\n0,0\n1,0.1\n");
    EXPECT_EQ(read(p), kept);  // the rows after the mark are gone
    j.append("2,0.2\n");
    const JournalMark next = j.flush();
    EXPECT_EQ(next.length, 23u);
    EXPECT_EQ(next.hash, fnv1a("step,t\n0,0\n1,0.1\n2,0.2\n"));
  }
  EXPECT_EQ(read(p), "step,t\n0,0\n1,0.1\n2,0.2\n");

  std::string bad = read(p);
  bad[3] = 'P';
  write(p, bad);
  EXPECT_THROW(Journal(p, mark, &kept), InputError) << "a changed byte before the mark";
  write(p, "step,t\n");
  EXPECT_THROW(Journal(p, mark, &kept), InputError) << "shorter than the mark";
  EXPECT_THROW(Journal(scratch("no_journal.csv"), mark, &kept), InputError);
}
