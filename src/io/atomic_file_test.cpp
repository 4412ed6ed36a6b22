#include "io/atomic_file.hpp"

#include <gtest/gtest.h>

#include "common/test_files.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "common/errors.hpp"

namespace dsswarm {
namespace {

using test::fresh_dir;

namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(AtomicFile, WritesContents) {
  const fs::path p = fresh_dir("atomic_writes") / "a.txt";
  write_file_atomically(p, "hello\n");
  EXPECT_EQ(slurp(p), "hello\n");
}

TEST(AtomicFile, FailedWriteKeepsOldFileAndLeavesNoTemporary) {
  const fs::path dir = fresh_dir("atomic_fail");
  const fs::path p = dir / "a.txt";
  write_file_atomically(p, "old");
  EXPECT_THROW(write_file_atomically(p, [](std::ostream& out) {
                 out << "partial";
                 throw std::runtime_error("boom");
               }),
               std::runtime_error);
  EXPECT_EQ(slurp(p), "old");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

TEST(AtomicFile, MissingDirectoryIsAClearError) {
  try {
    write_file_atomically(fs::path(DSSWARM_TEST_TMP) / "no/such/dir/x.txt", "x");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos);
  }
}

}  // namespace
}  // namespace dsswarm
