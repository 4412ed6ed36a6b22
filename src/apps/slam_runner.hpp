#pragma once
// Runs the SLAM pipeline over a recorded log, with a progress line on stderr,
// and writes the standard outputs of `dsswarm run` / `dsswarm demo`.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/trajectory/tum.hpp"
#include "sensor/laser_scan.hpp"
#include "slam/slam.hpp"

namespace dsswarm {

struct RunResult {
  Trajectory trajectory;         // one pose per scan of the log, file order
  std::size_t scans_read = 0;
  std::size_t scans_matched = 0;
  double wall_seconds = 0.0;     // SLAM processing only (no reading, no writing)
};

// Feeds every scan of `log` to `slam`. Prints a progress line to stderr every
// couple of seconds when `label` is not empty and the run takes that long.
RunResult run_slam(const SensorLog& log, Slam& slam, const std::string& label = "run");

// stats.json contents: the keys promised in the README.
nlohmann::json run_stats(const RunResult& result, const Slam& slam, const SensorLog& log, double read_seconds);

// Writes trajectory.tum, map.pgm + map.yaml (ROS map_server), map.png (map with
// the trajectory, and `ground_truth` in another colour if given), stats.json.
// Each file is written atomically; the directory is created if needed.
void write_run_outputs(const std::filesystem::path& dir, const RunResult& result, const Slam& slam,
                       const nlohmann::json& stats, const Trajectory* ground_truth = nullptr);

// Peak resident set size of this process, bytes.
std::size_t peak_rss_bytes();

}  // namespace dsswarm
