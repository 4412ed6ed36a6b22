#pragma once
// Scratch files for tests (only tests include this: DSSWARM_TEST_TMP is
// defined for test executables by dsswarm_test()).
#include <filesystem>
#include <fstream>
#include <string>

namespace dsswarm::test {

// An empty directory DSSWARM_TEST_TMP/name (removed and re-created).
inline std::filesystem::path fresh_dir(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(DSSWARM_TEST_TMP) / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// Writes `text` to `path` and returns the path.
inline std::filesystem::path write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path) << text;
  return path;
}

}  // namespace dsswarm::test
