#include "apps/slam_runner.hpp"

#include <fmt/core.h>
#include <sys/resource.h>

#include <algorithm>
#include <chrono>

#include "common/errors.hpp"
#include "config/config_json.hpp"
#include "io/atomic_file.hpp"
#include "io/maps/annotate.hpp"
#include "io/maps/dsmap.hpp"
#include "io/maps/map_server.hpp"
#include "io/maps/render.hpp"
#include "swarm/map_merge.hpp"

namespace dsswarm {

using Clock = std::chrono::steady_clock;

constexpr Rgb kGroundTruthColour{40, 170, 60};

namespace {

RunResult run(const SensorLog& log, Slam& slam, const std::string& label, SensorLog* release) {
  RunResult result;
  const auto start = Clock::now();
  auto next_report = start + std::chrono::seconds(2);
  const std::size_t total = log.scans.size();
  const std::size_t first_index = slam.scans_processed();  // step indices count every scan the Slam saw
  for (std::size_t i = 0; i < total; ++i) {
    slam.process(log.scans[i]);
    if (release) std::vector<float>().swap(release->scans[i].ranges);
    if (!label.empty() && (i & 63) == 0 && Clock::now() >= next_report) {
      const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
      const double rate = static_cast<double>(i + 1) / elapsed;
      fmt::print(stderr, "[{}] {}/{} scans ({:.0f}%), {:.0f} scans/s, about {:.0f} s left\n", label, i + 1, total,
                 100.0 * static_cast<double>(i + 1) / static_cast<double>(total), rate,
                 static_cast<double>(total - i - 1) / rate);
      next_report = Clock::now() + std::chrono::seconds(2);
    }
  }
  slam.finish();
  result.wall_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  const std::vector<Pose2> optimized = slam.trajectory(), local = slam.local_trajectory();
  result.trajectory.reserve(total);
  result.frontend.reserve(total);
  for (std::size_t i = 0; i < total; ++i) {
    result.trajectory.push_back({log.scans[i].timestamp, optimized[first_index + i]});
    result.frontend.push_back({log.scans[i].timestamp, local[first_index + i]});
  }
  result.scans_read = total;
  result.scans_matched = slam.scans_matched();
  return result;
}

}  // namespace

RunResult run_slam(const SensorLog& log, Slam& slam, const std::string& label) {
  return run(log, slam, label, nullptr);
}

RunResult run_slam_releasing(SensorLog& log, Slam& slam, const std::string& label) {
  return run(log, slam, label, &log);
}

nlohmann::json run_stats(const RunResult& result, const Slam& slam, const SensorLog& log, double read_seconds,
                         bool map_figures) {
  nlohmann::json j;
  j["source"] = log.source;
  j["scans_read"] = result.scans_read;
  for (const auto& [name, count] : slam.scan_counters()) j[name] = count;
  j["scans_dropped"] = slam.scans_dropped();
  j["drop_ratio"] = result.scans_read > 0 ? static_cast<double>(slam.scans_dropped()) / static_cast<double>(result.scans_read) : 0.0;
  j["filter_seconds"] = slam.filter_seconds();
  j["wall_seconds"] = result.wall_seconds;
  j["scans_per_second"] = result.wall_seconds > 0 ? static_cast<double>(result.scans_read) / result.wall_seconds : 0.0;
  j["read_seconds"] = read_seconds;
  j["peak_rss_bytes"] = peak_rss_bytes();
  if (map_figures) {
    const MultiResMap& map = slam.map();
    const std::size_t cells = map.cells_allocated(), bytes = map.memory_bytes();
    j["cells_allocated"] = cells;
    j["map_bytes"] = bytes;
    j["bytes_per_cell"] = cells > 0 ? static_cast<double>(bytes) / static_cast<double>(cells) : 0.0;
  }
  j["submaps"] = slam.submaps().finished().size() + (slam.submaps().current().scans > 0 ? 1 : 0);
  j["submap_bytes"] = slam.submaps().memory_bytes();
  const LoopCloser& closer = slam.loop_closer();
  const LoopClosureStats& lc = closer.stats();
  j["loop_closure"] = {{"nodes", closer.nodes()},
                       {"graph_bytes", closer.memory_bytes()},
                       {"rounds", lc.rounds},
                       {"optimizations", lc.optimizations},
                       {"searches", lc.searches},
                       {"skipped_closed", lc.skipped_closed},
                       {"candidates", lc.candidates},
                       {"accepted", lc.accepted},
                       {"rejected",
                        {{"no_match", lc.rejected_no_match},
                         {"unknown", lc.rejected_unknown},
                         {"inliers", lc.rejected_inliers},
                         {"same_side", lc.rejected_same_side},
                         {"ambiguous", lc.rejected_ambiguous},
                         {"prior_fits", lc.rejected_prior_fits},
                         {"inconsistent", lc.rejected_inconsistent},
                         {"residual", lc.rejected_residual}}},
                       {"round_seconds", lc.background_seconds}};
  j["warnings"] = log.warnings;
  j["config"] = to_json(slam.config());
  return j;
}

bool has_returns(const std::vector<LaserScan>& scans) {
  return std::any_of(scans.begin(), scans.end(), [](const LaserScan& s) { return s.valid_count() > 0; });
}

void require_returns(const SensorLog& log) {
  if (!log.scans.empty() && !has_returns(log.scans))
    throw InputError(fmt::format("{}: no scan has a valid return: every reading of the {} scans is NaN, inf, at or "
                                 "below the minimum range or at or beyond the maximum range ({} m): nothing to map",
                                 log.source, log.scans.size(), log.scans.front().range_max));
}

OutputFiles run_output_files(const std::filesystem::path& dir, const RunResult& result, const Slam& slam,
                             const nlohmann::json& stats, const Trajectory* ground_truth, bool images) {
  if (!slam.holds_evidence())
    throw InputError("the map is empty: no scan point was inserted (see points.min_range and points.max_range)");
  OutputFiles files;
  files.add(dir / "trajectory.tum", format_tum(dir / "trajectory.tum", result.trajectory));
  files.add(dir / "trajectory_frontend.tum", format_tum(dir / "trajectory_frontend.tum", result.frontend));
  if (!images) {
    files.add(dir / "stats.json", stats.dump(2) + "\n");
    return files;
  }
  GridRaster raster = slam.map().finest().to_raster();
  add_map_server(files, dir / "map.yaml", raster);
  Image picture = render_map(raster, fitting_scale(raster));
  auto path_of = [](const Trajectory& t) {
    std::vector<Eigen::Vector2d> pts;
    pts.reserve(t.size());
    for (const auto& p : t) pts.push_back(p.pose.translation());
    return pts;
  };
  std::vector<LegendEntry> legend;
  if (ground_truth) {
    draw_path(picture, raster, path_of(*ground_truth), kGroundTruthColour);
    legend.push_back({"ground truth", kGroundTruthColour});
  }
  draw_path(picture, raster, path_of(result.trajectory), agent_colour(0));
  legend.push_back({"trajectory", agent_colour(0)});
  if (!result.trajectory.empty()) {
    draw_ringed_marker(picture, raster, result.trajectory.front().pose.translation(), agent_colour(0), 4);
    legend.push_back({"start", agent_colour(0), LegendEntry::Mark::Disc});
  }
  const double metres_per_pixel = raster.resolution * raster.width / picture.width;
  std::vector<DsMass>().swap(raster.cells);  // drawn: its memory goes before the legend's copy and the PNG
  picture = with_legend(picture, metres_per_pixel, legend);
  files.add(dir / "map.png", encode_png(dir / "map.png", picture));
  files.add(dir / "stats.json", stats.dump(2) + "\n");
  return files;
}

void write_run_outputs(const std::filesystem::path& dir, const RunResult& result, const Slam& slam,
                       const nlohmann::json& stats, const Trajectory* ground_truth) {
  run_output_files(dir, result, slam, stats, ground_truth).write_all();
}

MapSnapshot own_map_snapshot(const Slam& slam, const std::string& sender, std::uint64_t previous_version) {
  MapSnapshot snapshot;
  snapshot.sender = sender;
  snapshot.layers.push_back({sender, previous_version + slam.scans_inserted(), Pose2(), 0,
                             std::make_shared<const MultiResMap>(slam.own_map()), {}});
  return snapshot;
}

ContinuedMap load_map_to_continue(const std::string& path, SlamConfig& config) {
  const MapSnapshot snapshot = read_dsmap(path);
  if (snapshot.layers.empty()) throw InputError(path + ": the map file holds no map layer");
  const MapLayer& layer = snapshot.layers.front();
  const MapConfig& file = layer.map->config();
  if (file.resolution != config.map.resolution || file.levels != config.map.levels)
    throw InputError(fmt::format("{}: the map has resolution {} m and {} levels, the configuration {} m and {} levels "
                                 "(set map.resolution / map.levels or --resolution to match the file)",
                                 path, file.resolution, file.levels, config.map.resolution, config.map.levels));
  ContinuedMap result{MultiResMap(), layer.version, {}, {}};
  if (snapshot.layers.size() > 1)
    result.warnings.push_back(fmt::format("{}: {} layers; continuing in layer 0 ('{}', the sender's own map) only",
                                          path, snapshot.layers.size(), layer.origin));
  const EvidenceModel& ours = config.map.evidence;
  if (file.evidence.hit_occupied != ours.hit_occupied || file.evidence.pass_free != ours.pass_free ||
      file.evidence.min_unknown != ours.min_unknown)
    result.warnings.push_back(fmt::format(
        "{}: continuing with the map's evidence model (hit_occupied {}, pass_free {}, min_unknown {}) instead of "
        "the configuration's ({}, {}, {})",
        path, file.evidence.hit_occupied, file.evidence.pass_free, file.evidence.min_unknown, ours.hit_occupied,
        ours.pass_free, ours.min_unknown));
  // New evidence must be weighed as the old was; the other map settings
  // (how scans are inserted) stay the configuration's.
  config.map.evidence = file.evidence;
  result.map = MultiResMap(config.map);
  const MultiResMap evidence = layer_evidence(layer);  // submap pieces (a robot's checkpoint) in one map
  for (int l = 0; l < result.map.levels(); ++l) result.map.mutable_level(l) = evidence.level(l);
  const GridRaster extent = result.map.finest().to_raster();
  result.description = fmt::format(
      "layer 0 of {} ('{}', version {}), {} levels, {} m cells, {} cells allocated, {:.1f} m x {:.1f} m",
      snapshot.layers.size(), layer.origin, layer.version, file.levels, file.resolution,
      result.map.cells_allocated(), extent.width * extent.resolution, extent.height * extent.resolution);
  return result;
}

}  // namespace dsswarm
