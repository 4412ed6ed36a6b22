#include "io/maps/pgm.hpp"

#include <fmt/format.h>

#include <cctype>
#include <cstddef>

#include "common/errors.hpp"

namespace dsswarm {
namespace {

bool is_pgm_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f'; }

// A cursor over the file that knows its line number, so every error can say where.
class PgmCursor {
 public:
  PgmCursor(std::string_view bytes, const std::string& source) : bytes_(bytes), source_(source) {}

  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(fmt::format("{}: line {}: {}", source_, line_, what));
  }

  // Skips whitespace and '#' comments (a comment runs to the end of its line).
  void skip_space_and_comments() {
    while (pos_ < bytes_.size()) {
      const char c = bytes_[pos_];
      if (c == '#') {
        while (pos_ < bytes_.size() && bytes_[pos_] != '\n') ++pos_;
      } else if (is_pgm_space(c)) {
        advance();
      } else {
        return;
      }
    }
  }

  // Reads one unsigned decimal number; `what` names the field for errors.
  long read_number(const char* what, long max_value) {
    skip_space_and_comments();
    if (pos_ >= bytes_.size()) fail(fmt::format("file ends before the {}", what));
    if (!std::isdigit(static_cast<unsigned char>(bytes_[pos_]))) {
      fail(fmt::format("expected a number for the {}, found '{}'", what, printable(bytes_[pos_])));
    }
    long value = 0;
    while (pos_ < bytes_.size() && std::isdigit(static_cast<unsigned char>(bytes_[pos_]))) {
      value = value * 10 + (bytes_[pos_] - '0');
      if (value > max_value) fail(fmt::format("{} is larger than {}", what, max_value));
      ++pos_;
    }
    if (pos_ < bytes_.size() && !is_pgm_space(bytes_[pos_]) && bytes_[pos_] != '#') {
      fail(fmt::format("expected a number for the {}, found '{}'", what, printable(bytes_[pos_])));
    }
    return value;
  }

  bool at_end() const { return pos_ >= bytes_.size(); }
  char peek() const { return bytes_[pos_]; }
  void advance() {
    if (bytes_[pos_] == '\n') ++line_;
    ++pos_;
  }
  std::size_t remaining() const { return bytes_.size() - pos_; }
  std::string_view rest() const { return bytes_.substr(pos_); }

  static std::string printable(char c) {
    const auto u = static_cast<unsigned char>(c);
    return std::isprint(u) ? std::string(1, c) : fmt::format("\\x{:02x}", u);
  }

 private:
  std::string_view bytes_;
  const std::string& source_;
  std::size_t pos_ = 2;  // after the magic number
  int line_ = 1;
};

std::uint8_t to_full_range(long value, long maxval) {
  return static_cast<std::uint8_t>(maxval == 255 ? value : value * 255 / maxval);
}

// P5: the raster's bytes, exactly as many as the header says.
void read_binary_pixels(PgmCursor& cursor, long maxval, GreyImage& image) {
  const std::size_t count = static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
  // Exactly one whitespace character separates maxval from the raster.
  if (cursor.at_end()) cursor.fail("file ends after the header; no pixel data");
  cursor.advance();
  if (cursor.remaining() < count) {
    cursor.fail(fmt::format("truncated pixel data: header says {}x{} = {} bytes, file has {}", image.width,
                            image.height, count, cursor.remaining()));
  }
  if (cursor.remaining() > count) {
    cursor.fail(fmt::format("size mismatch: header says {}x{} = {} bytes, file has {} (trailing data)", image.width,
                            image.height, count, cursor.remaining()));
  }
  const std::string_view data = cursor.rest();
  image.pixels.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    const long v = static_cast<unsigned char>(data[i]);
    if (v > maxval) cursor.fail(fmt::format("pixel {} has value {} above maxval {}", i, v, maxval));
    image.pixels[i] = to_full_range(v, maxval);
  }
}

// P2: the values in text, separated by whitespace and comments.
void read_plain_pixels(PgmCursor& cursor, long maxval, GreyImage& image) {
  const std::size_t count = static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
  // Each value needs at least one digit and one separator, which bounds the
  // allocation by the file size even if the header lies.
  if (count > cursor.remaining()) {
    cursor.fail(fmt::format("truncated pixel data: header says {}x{} = {} values, file is too short", image.width,
                            image.height, count));
  }
  image.pixels.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    cursor.skip_space_and_comments();
    if (cursor.at_end()) {
      cursor.fail(fmt::format("truncated pixel data: header says {}x{} = {} values, found {}", image.width,
                              image.height, count, i));
    }
    const long v = cursor.read_number("pixel value", maxval);
    image.pixels[i] = to_full_range(v, maxval);
  }
  cursor.skip_space_and_comments();
  if (!cursor.at_end()) {
    cursor.fail(fmt::format("size mismatch: more than {}x{} = {} pixel values", image.width, image.height, count));
  }
}

}  // namespace

GreyImage parse_pgm(std::string_view bytes, const std::string& source_name) {
  if (bytes.size() < 2 || bytes[0] != 'P' || (bytes[1] != '5' && bytes[1] != '2')) {
    const bool png = bytes.size() >= 4 && bytes.substr(1, 3) == "PNG";
    throw InputError(fmt::format("{}: line 1: not a PGM image (expected magic number P5 or P2){}", source_name,
                                 png ? "; PNG map images are not supported, convert to PGM" : ""));
  }
  PgmCursor cursor(bytes, source_name);
  if (!cursor.at_end() && !is_pgm_space(cursor.peek()) && cursor.peek() != '#') {
    cursor.fail("not a PGM image (expected whitespace after the magic number)");
  }
  GreyImage image;
  image.width = static_cast<int>(cursor.read_number("width", kMaxPgmSide));
  image.height = static_cast<int>(cursor.read_number("height", kMaxPgmSide));
  const long maxval = cursor.read_number("maxval", 65535);
  if (image.width == 0 || image.height == 0) cursor.fail(fmt::format("empty image ({}x{})", image.width, image.height));
  if (maxval == 0) cursor.fail("maxval is 0");
  if (maxval > 255) cursor.fail(fmt::format("16-bit PGM (maxval {}) is not supported; use maxval 255", maxval));
  if (bytes[1] == '5') read_binary_pixels(cursor, maxval, image);
  else read_plain_pixels(cursor, maxval, image);
  return image;
}

}  // namespace dsswarm
