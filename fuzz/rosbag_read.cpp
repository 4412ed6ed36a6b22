// Whole ROS1 bags through read_rosbag: our structural check, then
// rosbag_storage and our message decoding, time ordering and odometry
// lookup, with odometry from the odom topic and from /tf.
#include <cmath>

#include "common/errors.hpp"
#include "fuzz_support.hpp"
#include "io/rosbag/rosbag_reader.hpp"
#include "rosbag_common.hpp"

namespace dsswarm::fuzz {

void write_seeds(Seeds& seeds) {
  // Uncompressed chunks: changes to the messages pass the structural check
  // and reach the decoding.
  using Compression = rosbag_raw::TestBagSpec::Compression;
  seeds.add("odometry.bag", seed_bag(false, Compression::None));
  seeds.add("scans-only.bag", seed_bag(true, Compression::None));
  seeds.dictionary(rosbag_dictionary());
}

}  // namespace dsswarm::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace dsswarm;
  const auto path = fuzz::scratch_file("input.bag", fuzz::as_text(data, size));
  // One read per input (opening a bag loads rosbag_storage's plugins: slow);
  // the length's parity picks the odometry source, so mutations try both.
  const bool use_tf = size % 2 == 1;
  fuzz::expect_clean<InputError>(path.string(), [&] {
    const SensorLog log = read_rosbag(path, RosbagOptions{"/scan", "/odom", use_tf});
    for (const LaserScan& scan : log.scans) {
      fuzz::check(std::isfinite(scan.angle_min) && std::isfinite(scan.angle_increment), "scan geometry is not finite");
      fuzz::check(!scan.odometry || (std::isfinite(scan.odometry->x) && std::isfinite(scan.odometry->y) &&
                                     std::isfinite(scan.odometry->theta)),
                  "scan odometry is not finite");
    }
  });
  return 0;
}
