#include "bench_fixture.hpp"

#include "sim/scenario.hpp"

namespace dsswarm::bench {

Fixture::Fixture() : run(simulate_demo(DemoConfig{})) {
  for (int i = 0; i < kMapScans; ++i) pose = slam.process(run.log.scans[static_cast<std::size_t>(i)]).pose;
  scan = run.log.scans[kMapScans];
  points = scan_to_points(scan);
}

const Fixture& fixture() {
  static const Fixture f;
  return f;
}

}  // namespace dsswarm::bench
