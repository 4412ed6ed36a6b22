// TUM trajectories: read_tum on a stream.
#include <cmath>
#include <sstream>

#include "common/errors.hpp"
#include "fuzz_support.hpp"
#include "io/trajectory/tum.hpp"

namespace dsswarm::fuzz {

void write_seeds(Seeds& seeds) {
  // As write_tum writes them, and as the unit tests read them from 3D tools.
  seeds.add("written.tum",
            "# timestamp x y z qx qy qz qw\n"
            "12.500000 1.000000000 -2.000000000 0.000000 0.000000000 0.000000000 0.707106781 0.707106781\n"
            "976052904.900000 -1234.567891000 0.000001000 0.000000 0.000000000 0.000000000 -0.997494987 "
            "0.070737202\n");
  seeds.add("3d.tum",
            "# written by some 3D tool\n\n"
            "100.0 1.0 2.0 0.5 -0.004161148 0.111344157 0.472055466 0.874499171\r\n   \t\n"
            "101.0 1.1 2.1 0.5 0 0 0 1\n");
  seeds.add("bad.tum", "1 2 3\n1.0 0 0 0 0 0 0 2\n");
  seeds.dictionary({"# ", "nan", "inf", "1e308", "-0", "0.707106781", "\r\n"});
}

}  // namespace dsswarm::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace dsswarm;
  const std::string source = "fuzz.tum";
  std::istringstream in{std::string(fuzz::as_text(data, size))};
  fuzz::expect_clean<InputError>(source, [&] {
    for (const StampedPose& p : read_tum(in, source)) {
      fuzz::check(std::isfinite(p.timestamp) && std::isfinite(p.pose.x) && std::isfinite(p.pose.y) &&
                      std::isfinite(p.pose.theta),
                  "a pose read is not finite");
    }
  });
  return 0;
}
