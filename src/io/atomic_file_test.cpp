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

TEST(AtomicFile, ErrorsNameTheFileNotTheTemporary) {
  try {
    write_file_atomically("/proc/dsswarm_atomic_test", "x");  // /proc takes no new files, not even as root
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("cannot write /proc/dsswarm_atomic_test"), std::string::npos) << message;
    EXPECT_EQ(message.find(".tmp"), std::string::npos) << message;
  }
}

TEST(OutputFiles, WritesEveryFileCreatingFolders) {
  const fs::path dir = fresh_dir("output_files_all");
  OutputFiles files;
  files.add(dir / "a.txt", "a");
  files.add(dir / "sub" / "b.txt", "b");
  files.add(dir / "a.txt", "a2");  // replaces the first
  ASSERT_EQ(files.files().size(), 2u);
  files.write_all();
  EXPECT_EQ(slurp(dir / "a.txt"), "a2");
  EXPECT_EQ(slurp(dir / "sub" / "b.txt"), "b");
}

TEST(OutputFiles, OneFailureWritesNothing) {
  const fs::path dir = fresh_dir("output_files_none");
  write_file_atomically(dir / "a.txt", "old");
  write_file_atomically(dir / "blocker", "a file where a folder is needed");
  OutputFiles files;
  files.add(dir / "a.txt", "new");
  files.add(dir / "blocker" / "b.txt", "b");
  try {
    files.write_all();
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("blocker"), std::string::npos) << e.what();
  }
  EXPECT_EQ(slurp(dir / "a.txt"), "old");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 2);  // no temporaries
}

}  // namespace
}  // namespace dsswarm
