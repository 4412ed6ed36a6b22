// Whole ROS 2 bags through read_rosbag2: a bag folder whose metadata.yaml
// names one MCAP file, the input, so the fuzzer's changes go through the
// MCAP reader, the CDR decoding, time ordering and odometry lookup.
#include <cmath>

#include "common/errors.hpp"
#include "fuzz_support.hpp"
#include "io/rosbag2/rosbag2_reader.hpp"
#include "rosbag2_common.hpp"

namespace dsswarm::fuzz {

void write_seeds(Seeds& seeds) {
  using rosbag2_test::Format;
  // Uncompressed: changes to the messages reach the decoding.
  seeds.add("unchunked.mcap", rosbag2_seed_bag(Format::McapUnchunked).storage);
  seeds.add("chunked.mcap", rosbag2_seed_bag(Format::McapChunked).storage);
  seeds.dictionary(rosbag2_dictionary());
}

}  // namespace dsswarm::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace dsswarm;
  static const std::filesystem::path dir = [] {
    std::filesystem::create_directories(fuzz::scratch_dir() / "bag2");
    fuzz::scratch_file("bag2/metadata.yaml",
                       "rosbag2_bagfile_information:\n  version: 5\n  storage_identifier: mcap\n"
                       "  relative_file_paths: [run_0.mcap]\n");
    return fuzz::scratch_dir() / "bag2";
  }();
  fuzz::scratch_file("bag2/run_0.mcap", fuzz::as_text(data, size));
  // The length's parity picks the odometry source, so mutations try both.
  const BagReadOptions options{"/scan", "/odom", size % 2 == 1};
  fuzz::expect_clean<InputError>(dir.string(), [&] {
    for (const LaserScan& scan : read_rosbag2(dir, options).scans) {
      fuzz::check(std::isfinite(scan.angle_min) && std::isfinite(scan.angle_increment), "scan geometry is not finite");
      fuzz::check(!scan.odometry || (std::isfinite(scan.odometry->x) && std::isfinite(scan.odometry->y) &&
                                     std::isfinite(scan.odometry->theta)),
                  "scan odometry is not finite");
    }
  });
  return 0;
}
