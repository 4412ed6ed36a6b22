#pragma once
// Runs the SLAM pipeline over a recorded log, with a progress line on stderr,
// and writes the standard outputs of `dsswarm run` / `dsswarm demo`.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "common/process_usage.hpp"
#include "io/atomic_file.hpp"
#include "io/trajectory/tum.hpp"
#include "sensor/laser_scan.hpp"
#include "slam/slam.hpp"
#include "swarm/map_snapshot.hpp"

namespace dsswarm {

struct RunResult {
  Trajectory trajectory;         // one pose per scan of the log, file order: optimized (after loop closing)
  Trajectory frontend;           // the same scans as local SLAM first estimated them (its local frame)
  std::size_t scans_read = 0;
  std::size_t scans_matched = 0;
  double wall_seconds = 0.0;     // SLAM processing only (no reading, no writing)
};

// Feeds every scan of `log` to `slam`, then finishes it (the last loop-closing
// round is part of the run). Prints a progress line to stderr every couple of
// seconds when `label` is not empty and the run takes that long.
RunResult run_slam(const SensorLog& log, Slam& slam, const std::string& label = "run");
// The same, letting go of each scan's ranges once processed (the timestamps
// stay): like a robot, which keeps its map and not its scans, a run then
// holds only the part of the log still to come.
RunResult run_slam_releasing(SensorLog& log, Slam& slam, const std::string& label = "run");

// stats.json contents: the keys promised in the README. `map_figures` false
// leaves out the global map's cells and bytes: with loop closure the map is
// composed from its submaps for them, work wasted when no map is written.
nlohmann::json run_stats(const RunResult& result, const Slam& slam, const SensorLog& log, double read_seconds,
                         bool map_figures = true);

// Whether any of `scans` has a valid return (a reading the map can use).
bool has_returns(const std::vector<LaserScan>& scans);

// InputError naming the log unless some scan has a valid return: a log of
// nothing but max-range readings would give an empty map.
void require_returns(const SensorLog& log);

// trajectory.tum (optimized), trajectory_frontend.tum (as first estimated),
// map.pgm + map.yaml (ROS map_server), map.png (map with the
// trajectory, and `ground_truth` in another colour if given), stats.json, in
// memory (without `images`, trajectory.tum and stats.json only): InputError if
// the map is empty, before anything is written.
OutputFiles run_output_files(const std::filesystem::path& dir, const RunResult& result, const Slam& slam,
                             const nlohmann::json& stats, const Trajectory* ground_truth = nullptr,
                             bool images = true);

// Writes run_output_files (all of them or none); the directory is created if needed.
void write_run_outputs(const std::filesystem::path& dir, const RunResult& result, const Slam& slam,
                       const nlohmann::json& stats, const Trajectory* ground_truth = nullptr);

// The robot's own map as a one-layer snapshot (what `run --save-map` writes):
// origin = sender, identity pose, hops 0, version = `previous_version` (the
// version of a map the run continued in) + the scans this run inserted.
MapSnapshot own_map_snapshot(const Slam& slam, const std::string& sender, std::uint64_t previous_version = 0);

// A saved map to continue mapping in (`run --load-map`).
struct ContinuedMap {
  MultiResMap map;                    // layer 0 of the file, with `config`'s insertion settings
  std::uint64_t version = 0;          // the layer's version (scans already in it)
  std::vector<std::string> warnings;  // extra layers ignored, evidence model taken from the file
  // What was loaded, one line: layer, version, levels, resolution, cells, extent.
  std::string description;
};

// Reads layer 0 of the .dsmap file `path`. Throws InputError naming the file
// and both values when its resolution or level count differs from
// `config.map`'s, or when it holds no layer. The map keeps the evidence model
// it was built with: `config.map.evidence` is set to the file's.
ContinuedMap load_map_to_continue(const std::string& path, SlamConfig& config);


}  // namespace dsswarm
