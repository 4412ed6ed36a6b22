// PGM map images (map_server maps read back): parse_pgm on bytes.
#include "common/errors.hpp"
#include "fuzz_support.hpp"
#include "io/maps/pgm.hpp"

namespace dsswarm::fuzz {

void write_seeds(Seeds& seeds) {
  seeds.add("comments.pgm", std::string("P5#c1\n2#c2\n#c3\n 1\n#c4\n255\n") + '\x07' + '\xff');
  seeds.add("plain.pgm", "P2 3 1 100 0 50 100");
  seeds.add("binary.pgm", std::string("P5 2 1 1\n") + '\x00' + '\x01');
  seeds.add("wide.pgm", "P5\n4 2\n255\n\x01\x02\x03\x04\xfe\xfd\xfc\xfb");
  seeds.dictionary({"P2", "P5", "#", "255", "65535", "100000", "\x89PNG"});
}

}  // namespace dsswarm::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace dsswarm;
  const std::string source = "fuzz.pgm";
  fuzz::expect_clean<InputError>(source, [&] {
    const GreyImage image = parse_pgm(fuzz::as_text(data, size), source);
    fuzz::check(image.width > 0 && image.height > 0 &&
                    image.pixels.size() == static_cast<std::size_t>(image.width) * image.height,
                "image size disagrees with its pixels");
  });
  return 0;
}
