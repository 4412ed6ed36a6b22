#include "io/output_paths.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "common/errors.hpp"
#include "common/test_files.hpp"

namespace dsswarm {
namespace {

namespace fs = std::filesystem;
using test::fresh_dir;

// The ConfigError message of `check` ("" if it passed).
template <class Check>
std::string refusal(Check check) {
  try {
    check();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

std::size_t entries(const fs::path& dir) {
  return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

TEST(OutputPaths, UsableLocationsPassAndNothingIsCreated) {
  const fs::path dir = fresh_dir("output_paths_ok");
  test::write_text(dir / "old.dsmap", "x");
  EXPECT_EQ(refusal([&] { check_output_directory(dir, "--out"); }), "");
  EXPECT_EQ(refusal([&] { check_output_directory(dir / "new" / "deeper", "--out"); }), "");
  EXPECT_EQ(refusal([&] { check_output_file(dir / "old.dsmap", "--save-map"); }), "");  // replaced at the end
  EXPECT_EQ(refusal([&] { check_output_file(dir / "sub" / "new.png", "--plot"); }), "");
  EXPECT_EQ(entries(dir), 1u);  // the probes are gone, no folder was made
}

TEST(OutputPaths, FileWhereAFolderIsWantedAndTheOtherWayRound) {
  const fs::path dir = fresh_dir("output_paths_kinds");
  const fs::path file = test::write_text(dir / "a_file", "x");
  EXPECT_EQ(refusal([&] { check_output_directory(file, "--out"); }),
            "--out " + file.string() + ": exists and is not a folder");
  EXPECT_EQ(refusal([&] { check_output_directory(file / "sub", "--out"); }),
            "--out " + (file / "sub").string() + ": " + file.string() + " is not a folder");
  EXPECT_EQ(refusal([&] { check_output_file(dir, "--save-map"); }),
            "--save-map " + dir.string() + ": is a folder, not a file");
  EXPECT_EQ(refusal([&] { check_output_file(file / "x.png", "--plot"); }),
            "--plot " + (file / "x.png").string() + ": " + file.string() + " is not a folder");
  EXPECT_NE(refusal([&] { check_output_file("/dev/null", "--decisions"); }).find("not a regular file"), std::string::npos);
}

TEST(OutputPaths, PlacesWhereNothingCanBeCreatedAreRefused) {
  const std::string proc = refusal([] { check_output_directory("/proc/dsswarm_out", "--out"); });
  EXPECT_NE(proc.find("--out /proc/dsswarm_out: cannot create a folder in /proc"), std::string::npos) << proc;
  const std::string proc_file = refusal([] { check_output_file("/proc/x/map.dsmap", "--save-map"); });
  EXPECT_NE(proc_file.find("--save-map /proc/x/map.dsmap: cannot create a folder in /proc"), std::string::npos)
      << proc_file;
}

TEST(OutputPaths, FolderWithoutWritePermissionIsRefused) {
  if (::geteuid() == 0) GTEST_SKIP() << "root writes into read-only folders: the permission case needs a user";
  const fs::path locked = fresh_dir("output_paths_locked");
  fs::permissions(locked, fs::perms::owner_read | fs::perms::owner_exec);
  EXPECT_NE(refusal([&] { check_output_directory(locked, "--out"); }).find("cannot write in"), std::string::npos);
  EXPECT_NE(refusal([&] { check_output_file(locked / "a.log", "--out"); }).find("cannot write in"), std::string::npos);
  fs::permissions(locked, fs::perms::owner_all);
}

}  // namespace
}  // namespace dsswarm
