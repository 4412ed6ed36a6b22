// Whole ROS1 bags through read_rosbag: our structural check, then
// rosbag_storage and our message decoding, time ordering and odometry
// lookup, with odometry from the odom topic and from /tf.
#include <dlfcn.h>
#include <link.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <string_view>

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

namespace {

// rosbag_storage loads its encryption plugin (pluginlib, dlopen) at every
// Bag::open and unloads it at close, and every unload walks glibc's list of
// exit handlers, which keeps growing: an input took 2 ms at first and 20 ms
// after 3000. Holding the plugin library open for good (it sits beside
// librosbag_storage, or in its ros/ folder on Debian) keeps it loaded.
void keep_rosbag_plugin_loaded() {
  std::string dir;
  dl_iterate_phdr(
      [](dl_phdr_info* info, std::size_t, void* out) {
        const std::string_view name = info->dlpi_name;
        if (name.find("/librosbag_storage.so") == std::string_view::npos) return 0;
        *static_cast<std::string*>(out) = name.substr(0, name.rfind('/'));
        return 1;
      },
      &dir);
  for (const char* folder : {"/ros/", "/"}) {
    if (dlopen((dir + folder + "librosbag_default_encryption_plugins.so").c_str(), RTLD_NOW | RTLD_NODELETE)) return;
  }
  std::fprintf(stderr, "note: rosbag_storage's plugin library not found beside %s: fuzzing slows down\n", dir.c_str());
}

}  // namespace
}  // namespace dsswarm::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace dsswarm;
  static const bool kept = (fuzz::keep_rosbag_plugin_loaded(), true);
  (void)kept;
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
