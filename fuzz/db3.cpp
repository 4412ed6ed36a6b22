// ROS 2 bags' SQLite storage (src/io/rosbag2/db3_reader.cpp): read_db3_bytes,
// every message handed over (and its bytes read, for ASan to check).
#include <vector>

#include "common/errors.hpp"
#include "fuzz_support.hpp"
#include "io/rosbag2/db3_reader.hpp"
#include "rosbag2_common.hpp"

namespace dsswarm::fuzz {

void write_seeds(Seeds& seeds) {
  seeds.add("small.db3", rosbag2_seed_bag(rosbag2_test::Format::Db3).storage);
  seeds.dictionary({"SQLite format 3", "topics", "messages", "CREATE TABLE", "serialization_format", "cdr",
                    "/scan", "/odom", "/tf", "sensor_msgs/msg/LaserScan"});
}

}  // namespace dsswarm::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace dsswarm;
  const std::string source = "fuzz.db3";
  std::vector<std::uint8_t> bytes(data, data + size);  // SQLite takes a writable buffer
  std::size_t checksum = 0;
  fuzz::expect_clean<InputError>(source, [&] {
    rosbag2::read_db3_bytes(
        bytes, source, [](const std::string&) { return true; },
        [&](const rosbag2::StoredMessage& m) {
          for (const std::uint8_t b : m.data) checksum += b;
        });
  });
  fuzz::keep(checksum);
  return 0;
}
