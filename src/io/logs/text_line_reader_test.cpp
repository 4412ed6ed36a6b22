#include "io/logs/text_line_reader.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "common/errors.hpp"
#include "io/logs/logs_test_util.hpp"

namespace dsswarm {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> all_lines(const fs::path& path) {
  TextLineReader reader(path);
  std::vector<std::string> lines;
  std::string_view line;
  while (reader.next(line)) {
    lines.emplace_back(line);
    EXPECT_EQ(reader.line_number(), lines.size());
  }
  EXPECT_FALSE(reader.next(line));  // stays at the end
  return lines;
}

TEST(TextLineReader, SplitsLinesOfPlainAndGzipFilesAlike) {
  const fs::path dir = test::scratch_dir("lines");
  // A line longer than the internal read chunk, to cross chunk boundaries.
  const std::string long_line(700 * 1024, 'x');
  const std::string text = "first\r\n\nthird\n" + long_line + "\nlast without newline";
  const std::vector<std::string> expected = {"first", "", "third", long_line, "last without newline"};
  test::write_plain(dir / "a.txt", text);
  test::write_gzip(dir / "a.txt.gz", text);
  EXPECT_EQ(all_lines(dir / "a.txt"), expected);
  EXPECT_EQ(all_lines(dir / "a.txt.gz"), expected);
  EXPECT_FALSE(TextLineReader(dir / "a.txt").compressed());
  EXPECT_TRUE(TextLineReader(dir / "a.txt.gz").compressed());
}

TEST(TextLineReader, EmptyFileHasNoLines) {
  const fs::path dir = test::scratch_dir("lines_empty");
  test::write_plain(dir / "e.txt", "");
  EXPECT_TRUE(all_lines(dir / "e.txt").empty());
  test::write_plain(dir / "one_gzip_byte.txt", "\x1f");
  EXPECT_EQ(all_lines(dir / "one_gzip_byte.txt"), std::vector<std::string>{"\x1f"});
}

TEST(TextLineReader, MissingFileNamesIt) {
  const fs::path path = test::scratch_dir("lines_missing") / "nope.txt";
  try {
    TextLineReader reader(path);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace dsswarm
