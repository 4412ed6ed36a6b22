// ROS 2 bags' MCAP storage (src/io/rosbag2/mcap_reader.cpp): read_mcap on a
// stream, every message handed over (and its bytes read, for ASan to check).
#include <sstream>

#include "common/errors.hpp"
#include "fuzz_support.hpp"
#include "io/rosbag2/mcap_reader.hpp"
#include "rosbag2_common.hpp"

namespace dsswarm::fuzz {

void write_seeds(Seeds& seeds) {
  using rosbag2_test::Format;
  seeds.add("unchunked.mcap", rosbag2_seed_bag(Format::McapUnchunked).storage);
  seeds.add("chunked.mcap", rosbag2_seed_bag(Format::McapChunked).storage);
  seeds.add("zstd.mcap", rosbag2_seed_bag(Format::McapZstd).storage);
  seeds.add("lz4.mcap", rosbag2_seed_bag(Format::McapLz4).storage);
  seeds.dictionary(rosbag2_dictionary());
}

}  // namespace dsswarm::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace dsswarm;
  const std::string source = "fuzz.mcap";
  std::istringstream in(std::string(fuzz::as_text(data, size)), std::ios::binary);
  std::size_t checksum = 0;
  fuzz::expect_clean<InputError>(source, [&] {
    rosbag2::read_mcap(
        in, size, source, [](const std::string&) { return true; },
        [&](const rosbag2::StoredMessage& m) {
          for (const std::uint8_t b : m.data) checksum += b;
        });
  });
  fuzz::keep(checksum);
  return 0;
}
