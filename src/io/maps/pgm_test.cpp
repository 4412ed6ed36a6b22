#include "io/maps/pgm.hpp"

#include <gtest/gtest.h>

#include "common/errors.hpp"

namespace dsswarm {
namespace {

std::string error_of(std::string_view bytes) {
  try {
    parse_pgm(bytes, "x.pgm");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(Pgm, CommentsMayAppearBetweenAnyHeaderFields) {
  const std::string bytes = std::string("P5#c1\n2#c2\n#c3\n 1\n#c4\n255\n") + '\x07' + '\xff';
  const GreyImage image = parse_pgm(bytes, "x.pgm");
  EXPECT_EQ(image.width, 2);
  EXPECT_EQ(image.height, 1);
  EXPECT_EQ(image.pixels, (std::vector<std::uint8_t>{7, 255}));
}

TEST(Pgm, SmallMaxvalIsRescaledToFullRange) {
  const GreyImage plain = parse_pgm("P2 3 1 100 0 50 100", "x.pgm");
  EXPECT_EQ(plain.pixels, (std::vector<std::uint8_t>{0, 127, 255}));
  const GreyImage binary = parse_pgm(std::string("P5 2 1 1\n") + '\x00' + '\x01', "x.pgm");
  EXPECT_EQ(binary.pixels, (std::vector<std::uint8_t>{0, 255}));
}

TEST(Pgm, ErrorsNameTheFileLineAndField) {
  EXPECT_NE(error_of("P5\n2 x\n255\n").find("x.pgm: line 2: expected a number for the height"), std::string::npos);
  EXPECT_NE(error_of("P2\n1 1\n9\n10\n").find("line 4: pixel value is larger than 9"), std::string::npos);
  EXPECT_NE(error_of("P5\n1 1\n65535\n\x01\x02").find("16-bit"), std::string::npos);
  EXPECT_NE(error_of("P5\n0 1\n255\n").find("empty image"), std::string::npos);
  EXPECT_NE(error_of("P5\n1 1\n255").find("no pixel data"), std::string::npos);
  EXPECT_NE(error_of("P5\n999999999 1\n255\n").find("width is larger than"), std::string::npos);
  EXPECT_NE(error_of("\x89PNG\r\n").find("PNG map images are not supported"), std::string::npos);
  EXPECT_NE(error_of("").find("not a PGM"), std::string::npos);
  EXPECT_NE(error_of("P5").find("file ends before the width"), std::string::npos);
}

TEST(Pgm, HugeHeaderWithLittleDataFailsWithoutAllocating) {
  // 100000 × 100000 would be 10 GB; the size check must come first.
  EXPECT_NE(error_of("P5\n100000 100000\n255\n\x01").find("truncated"), std::string::npos);
  EXPECT_NE(error_of("P2\n100000 100000\n255\n1 2 3").find("truncated"), std::string::npos);
}

}  // namespace
}  // namespace dsswarm
