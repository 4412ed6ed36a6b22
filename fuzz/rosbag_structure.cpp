// ROS1 bag records: the structural check (src/io/rosbag/bag_structure.cpp)
// that walks every record, chunk and index entry of a bag before
// rosbag_storage may open it.
#include <sstream>

#include "common/errors.hpp"
#include "fuzz_support.hpp"
#include "io/rosbag/bag_structure.hpp"
#include "rosbag_common.hpp"

namespace dsswarm::fuzz {

void write_seeds(Seeds& seeds) {
  // Chunks of each compression; the message contents do not matter here.
  using Compression = rosbag_raw::TestBagSpec::Compression;
  seeds.add("plain.bag", seed_bag(true, Compression::None));
  seeds.add("bz2.bag", seed_bag(true, Compression::Bz2));
  seeds.add("lz4.bag", seed_bag(true, Compression::Lz4));
  seeds.dictionary(rosbag_dictionary());
}

}  // namespace dsswarm::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace dsswarm;
  const std::string source = "fuzz.bag";
  std::istringstream in(std::string(fuzz::as_text(data, size)), std::ios::binary);
  fuzz::expect_clean<InputError>(source, [&] { rosbag_raw::check_bag_structure(in, source); });
  return 0;
}
