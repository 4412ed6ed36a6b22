// CARMEN log lines: parse_carmen on text in memory, under the file's own
// geometry and under the options a user can force (--beams span180,
// --laser-offset).
#include "carmen_common.hpp"
#include "common/errors.hpp"
#include "fuzz_support.hpp"
#include "io/logs/carmen_reader.hpp"

namespace dsswarm::fuzz {

void write_seeds(Seeds& seeds) {
  for (const auto& [name, text] : carmen_seed_logs(seeds)) seeds.add(name + ".log", text);
  seeds.dictionary(carmen_dictionary());
}

}  // namespace dsswarm::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace dsswarm;
  const std::string source = "fuzz.log";
  CarmenOptions forced;
  forced.beams = CarmenOptions::BeamConvention::Span180;
  forced.laser_offset = Pose2(0.1, 0.0, 0.05);
  for (const CarmenOptions& options : {CarmenOptions{}, forced}) {
    fuzz::expect_clean<InputError>(source, [&] { fuzz::check_log(parse_carmen(fuzz::as_text(data, size), source, options)); });
  }
  return 0;
}
