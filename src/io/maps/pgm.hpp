#pragma once
// Reading PGM (portable greymap) images, the format ROS map_server maps use.
// Internal to dsswarm_maps; writing is a few lines and lives with its caller.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace dsswarm {

struct GreyImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> pixels;  // row-major, row 0 = TOP of the picture, 0..255
};

// Largest side we accept when reading; a larger header is corrupt, not a map.
inline constexpr int kMaxPgmSide = 100000;

// Parses binary (P5) or plain (P2) PGM with '#' comments in the header.
// Values with maxval < 255 are rescaled to 0..255 (as SDL_image, which
// map_server loads through, does); maxval > 255 (16-bit) is refused.
// `source_name` only labels error messages: every error is an InputError
// "<source_name>: line N: ..." naming what was wrong.
GreyImage parse_pgm(std::string_view bytes, const std::string& source_name);

}  // namespace dsswarm
