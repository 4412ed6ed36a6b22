#include "agent/live_map_output.hpp"

#include <gtest/gtest.h>

#include <thread>
#include <vector>

#include "grid/test_cells.hpp"
#include "sim/test_laps.hpp"

namespace dsswarm::agent {
namespace {

// Records what /map would get; a map is due every 20th scan.
class Recorder : public RobotOutputs {
 public:
  void pose(double, const Pose2&, const std::optional<Pose2>&) override {}
  bool map_due(SteadyClock::time_point) const override { return ++asked % 20 == 0; }
  void map(GridRaster raster, double stamp) override { maps.emplace_back(std::move(raster), stamp); }
  std::vector<std::pair<GridRaster, double>> maps;
  mutable int asked = 0;
};

// Scans go on while the map is composed; after the last one, the next map
// published is the robot's whole map as its graph has it then.
void run_and_check(const SlamConfig& config, bool composed_off_the_scan_path) {
  const SimulatedRun run = test::lap(0, 1);
  const std::vector<LaserScan> scans(run.log.scans.begin(), run.log.scans.begin() + run.log.scans.size() / 3);
  SharedAgent shared(std::make_unique<SwarmAgent>("b", config), RelativePoseConfig{});
  Recorder recorder;
  LiveMapOutput output(shared, recorder);
  for (const LaserScan& scan : scans) {
    shared.process(scan);
    output.after_scan(scan.timestamp, SteadyClock::now());
  }
  shared.finish();
  ASSERT_FALSE(recorder.maps.empty());
  if (composed_off_the_scan_path) {  // the kept part holds finished submaps
    ASSERT_GT(shared.with_agent([](const SwarmAgent& a) { return a.slam().submaps().finished().size(); }), 1u);
  }
  const double last = scans.back().timestamp + 1.0;
  const auto deadline = SteadyClock::now() + std::chrono::seconds(30);
  while (recorder.maps.back().second != last && SteadyClock::now() < deadline) {
    output.after_scan(last, SteadyClock::now());
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_EQ(recorder.maps.back().second, last);
  const GridRaster now = shared.with_agent([](const SwarmAgent& a) { return a.slam().own_map().finest().to_raster(); });
  EXPECT_TRUE(test::same_cells(recorder.maps.back().first, now));
  EXPECT_EQ(output.composed() > 0, composed_off_the_scan_path);
}

TEST(LiveMapOutput, WithLoopClosureTheMapIsComposedOffTheScanPathAsTheGraphHasItNow) {
  run_and_check(with_loop_closure(), true);
}

TEST(LiveMapOutput, WithoutLoopClosureTheMapIsTheOneKeptScanByScan) {
  SlamConfig one_map;
  one_map.loop_closure.enabled = false;
  run_and_check(one_map, false);
}

}  // namespace
}  // namespace dsswarm::agent
