#pragma once
// The fixed input every micro-benchmark uses: the demo robot's simulated log
// (361 beams, seed 7), a map built by SLAM from its first 300 scans, and scan
// 300 with its pose. Deterministic: the same numbers on every run.
#include <vector>

#include "geometry/pose2.hpp"
#include "sensor/laser_scan.hpp"
#include "sensor/scan_points.hpp"
#include "sim/robot.hpp"
#include "slam/slam.hpp"

namespace dsswarm::bench {

inline constexpr int kMapScans = 300;

struct Fixture {
  Fixture();
  SimulatedRun run;
  Slam slam;                      // after the first kMapScans scans
  LaserScan scan;                 // scan kMapScans, the next one
  std::vector<ScanPoint> points;  // its points in the robot base frame
  Pose2 pose;                     // SLAM's pose of the last mapped scan
};

// Built once, on first use.
const Fixture& fixture();

}  // namespace dsswarm::bench
