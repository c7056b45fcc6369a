// test_atomic_file.cpp — io/cdyn/atomic_file: a file appears under its name complete
// or not at all, and the fields writer (fields.pvd, fields/step_*.vtu) uses it.
//
// Everything here is exact (file contents and directory listings), no tolerance.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "cdyn/atomic_file.hpp"
#include "cdyn/base/error.hpp"
#include "cdyn/fields_output.hpp"
#include "cdyn/problems/scalar_wave.hpp"

namespace fs = std::filesystem;
using namespace cdyn;

namespace {

// A fresh scratch directory per test.
fs::path scratch() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::temp_directory_path() /
                       ("cdyn_atomic_" + std::to_string(::getpid()) + "_" + info->name());
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string read(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

int count_entries(const fs::path& dir) {
  int n = 0;
  for (const auto& e : fs::directory_iterator(dir)) n += e.exists() ? 1 : 0;
  return n;
}

}  // namespace

TEST(AtomicFile, WritesTheContentAndLeavesNoTemporary) {
  const fs::path dir = scratch();
  write_file_atomically(dir / "summary.json", "{\"a\": 1}\n");
  EXPECT_EQ(read(dir / "summary.json"), "{\"a\": 1}\n");
  EXPECT_EQ(count_entries(dir), 1);
}

TEST(AtomicFile, TheTargetKeepsItsOldContentUntilCommit) {
  const fs::path dir = scratch();
  write_file_atomically(dir / "history.csv", "old\n");
  AtomicFile f(dir / "history.csv");
  f.stream() << "new, longer content\n";
  f.stream().flush();
  EXPECT_EQ(read(dir / "history.csv"), "old\n");  // a reader sees the old file meanwhile
  EXPECT_TRUE(fs::exists(f.temporary()));
  EXPECT_TRUE(is_atomic_temporary(f.temporary()));
  EXPECT_EQ(f.temporary().parent_path(), dir);  // same directory: rename is atomic
  f.commit();
  EXPECT_TRUE(f.committed());
  EXPECT_EQ(read(dir / "history.csv"), "new, longer content\n");
  EXPECT_EQ(count_entries(dir), 1);
  EXPECT_THROW(f.commit(), std::logic_error);
}

TEST(AtomicFile, AnUncommittedFileNeverAppears) {
  const fs::path dir = scratch();
  fs::path temporary;
  try {
    AtomicFile f(dir / "summary.json");
    temporary = f.temporary();
    f.stream() << "{\"partial\": ";
    throw NumericalError("interrupted");  // e.g. a failed step before commit()
  } catch (const NumericalError&) {
  }
  EXPECT_FALSE(fs::exists(dir / "summary.json"));
  EXPECT_FALSE(fs::exists(temporary));
  EXPECT_EQ(count_entries(dir), 0);
}

TEST(AtomicFile, AMissingDirectoryIsAnInputErrorNamingTheFile) {
  const fs::path dir = scratch();
  try {
    AtomicFile f(dir / "no_such_dir" / "summary.json");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no_such_dir/summary.json"), std::string::npos) << e.what();
  }
}

TEST(AtomicFile, StaleTemporariesAreRecognisedAndRemoved) {
  const fs::path dir = scratch();
  std::ofstream(dir / ".history.csv.tmp-12345-0") << "left by a killed run";
  std::ofstream(dir / "history.csv") << "a result";
  std::ofstream(dir / ".hidden.tmp-x") << "not ours";
  EXPECT_TRUE(is_atomic_temporary(dir / ".history.csv.tmp-12345-0"));
  EXPECT_FALSE(is_atomic_temporary(dir / "history.csv"));
  EXPECT_FALSE(is_atomic_temporary(dir / ".hidden.tmp-x"));
  EXPECT_FALSE(is_atomic_temporary(dir / "history.csv.tmp-1-2"));  // not hidden: not ours
  EXPECT_EQ(remove_stale_temporaries(dir), 1);
  EXPECT_TRUE(fs::exists(dir / "history.csv"));
  EXPECT_TRUE(fs::exists(dir / ".hidden.tmp-x"));
}

// The fields writer: complete files only, and remove_fields() clears what an
// interrupted run left (its frames and its temporaries).
TEST(AtomicFile, FieldsWriterLeavesOnlyCompleteFiles) {
  const fs::path dir = scratch();
  const Mesh mesh = interval_mesh(2);
  ScalarWaveData d;
  d.mass = cdyn::MassSpec::parse("P0", Element::P1);
  d.f = [](double, double, double) { return 0.0; };
  d.dirichlet_parts = {mesh.part_index("right")};
  d.dirichlet_value = [](double, double, double) { return 0.0; };
  d.obstacle_on_all_vertices = false;
  d.obstacle_parts = {mesh.part_index("left")};
  d.obstacle_g = [](double, double, double) { return 0.0; };
  const ConstrainedProblem p = build_scalar_wave(mesh, d);
  {
    FieldsWriter w(dir, mesh, p);
    const Eigen::VectorXd U = Eigen::VectorXd::LinSpaced(p.W->n_dofs(), 1.0, 0.0);
    w.write(0, 0.0, U, Eigen::VectorXd::Zero(U.size()), Eigen::VectorXd());
    w.write(1, 0.1, U, Eigen::VectorXd::Zero(U.size()), Eigen::VectorXd());
    w.finish();
  }
  EXPECT_EQ(count_entries(dir / "fields"), 2);  // step_000000.vtu, step_000001.vtu, no temporaries
  EXPECT_EQ(count_entries(dir), 2);            // fields/, fields.pvd
  const std::string pvd = read(dir / "fields.pvd");
  EXPECT_NE(pvd.find("file=\"fields/step_000001.vtu\""), std::string::npos);
  EXPECT_EQ(pvd.substr(pvd.size() - 11), "</VTKFile>\n");
  const std::string vtu = read(dir / "fields" / "step_000001.vtu");
  EXPECT_EQ(vtu.substr(vtu.size() - 11), "</VTKFile>\n");

  // what a killed run leaves: a frame's temporary and fields.pvd's
  std::ofstream(dir / "fields" / ".step_000002.vtu.tmp-999-7") << "<?xml";
  std::ofstream(dir / ".fields.pvd.tmp-999-8") << "<?xml";
  std::ofstream(dir / ".summary.json.tmp-999-9") << "{";  // not the fields' to remove
  remove_fields(dir);
  EXPECT_EQ(count_entries(dir / "fields"), 0);
  EXPECT_FALSE(fs::exists(dir / "fields.pvd"));
  EXPECT_FALSE(fs::exists(dir / ".fields.pvd.tmp-999-8"));
  EXPECT_TRUE(fs::exists(dir / ".summary.json.tmp-999-9"));
}
