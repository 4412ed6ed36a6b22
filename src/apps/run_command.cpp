#include "apps/run_command.hpp"

#include <fmt/core.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>

#include "apps/log_input.hpp"
#include "apps/slam_options.hpp"
#include "apps/slam_runner.hpp"
#include "common/errors.hpp"
#include "common/process_usage.hpp"
#include "config/config_json.hpp"
#include "io/logs/log_reader.hpp"
#include "io/maps/dsmap.hpp"
#include "io/output_paths.hpp"
#include "runtime/worker_thread.hpp"

namespace dsswarm {
namespace {

struct RunArgs {
  std::string log;
  std::string out;
  std::string scan_topic = "/scan";
  std::string odom_topic = "/odom";
  bool tf_odometry = false;
  bool odom_topic_named = false;  // --odom-topic given: a topic the bag lacks is an error
  std::string beams = "params";
  std::vector<double> laser_offset;
  std::string save_map;    // .dsmap written at the end (the robot's own map)
  std::string load_map;    // .dsmap to continue mapping in
  std::vector<double> start_pose;  // x y theta in the loaded map's frame
  std::size_t max_scans = 0;       // only the first N scans, 0: all (benchmarks, profiling)
  bool no_images = false;          // trajectory and stats only
  bool localize = false;   // with load_map: localize in it without changing it
  SlamOptions slam;
};

// Name of the robot in the maps it saves (`run` maps one robot).
constexpr const char* kRobotName = "robot";

void print_summary(const RunResult& r, const std::string& out) {
  fmt::print("{} scans, {} matched, {:.2f} s, {:.0f} scans/s; outputs in {}\n", r.scans_read, r.scans_matched,
             r.wall_seconds, r.wall_seconds > 0 ? static_cast<double>(r.scans_read) / r.wall_seconds : 0.0, out);
}

// The log as the flags say to read it, its warnings logged.
SensorLog read_run_log(const RunArgs& a, const std::optional<Pose2>& laser_offset, double& read_seconds) {
  LogReadOptions read;
  read.scan_topic = a.scan_topic;
  read.odom_topic = a.odom_topic;
  read.use_tf_odometry = a.tf_odometry;
  read.odom_topic_named = a.odom_topic_named;
  if (a.beams == "classic") read.carmen.beams = CarmenOptions::BeamConvention::Classic;
  if (a.beams == "span180") read.carmen.beams = CarmenOptions::BeamConvention::Span180;
  read.carmen.laser_offset = laser_offset;

  const auto t0 = std::chrono::steady_clock::now();
  SensorLog log = read_input_log(a.log, read);
  read_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (laser_offset)  // bags too: the flag overrides whatever the log says
    for (auto& s : log.scans) s.laser_offset = *laser_offset;
  require_returns(log);
  if (a.max_scans > 0 && log.scans.size() > a.max_scans) log.scans.resize(a.max_scans);
  return log;
}

void run(const RunArgs& a) {
  check_output_directory(a.out, "--out");  // output, config and map-file errors before any work
  if (!a.save_map.empty()) check_output_file(a.save_map, "--save-map");
  SlamConfig config = a.slam.resolve();
  std::optional<ContinuedMap> continued;
  if (!a.load_map.empty()) {
    continued = load_map_to_continue(a.load_map, config);
    for (const auto& w : continued->warnings) spdlog::warn("{}", w);
    fmt::print("loaded map {}: {}\n", a.load_map, continued->description);
  }
  // Filled in place, not copied from a temporary: GCC 12 for aarch64 warns
  // maybe-uninitialized on the optional<Pose2> copy (a false positive).
  std::optional<Pose2> start_pose, laser_offset;
  if (!a.start_pose.empty()) start_pose.emplace(pose_option(a.start_pose, "--start-pose"));
  if (!a.laser_offset.empty()) laser_offset.emplace(pose_option(a.laser_offset, "--laser-offset"));
  double read_seconds = 0.0;
  SensorLog log = read_run_log(a, laser_offset, read_seconds);

  // A loaded map is in the frame of the run that saved it, which began at its
  // first scan's odometry pose: the same log (or one recorded from the same
  // start) starts there by default.
  // Loop closing runs on a thread of its own (declared first: it outlives the Slam).
  WorkerThread background;
  std::unique_ptr<Slam> slam;
  if (continued) {
    const Pose2 start = start_pose ? *start_pose : log.scans.front().odometry.value_or(Pose2());
    slam = std::make_unique<Slam>(config, std::move(continued->map), start,
                                  a.localize ? MapUse::localize : MapUse::extend, &background);
  } else {
    slam = std::make_unique<Slam>(config, &background);
  }
  const double cpu0 = cpu_seconds();
  const RunResult result = run_slam_releasing(log, *slam);
  release_free_heap();  // the scans and the loop closer's working memory, before the outputs
  nlohmann::json stats = run_stats(result, *slam, log, read_seconds, !a.no_images || !a.save_map.empty());
  stats["cpu_seconds"] = cpu_seconds() - cpu0;
  stats["background_cpu_seconds"] = background.cpu_seconds();
  stats["waited_seconds"] = background.waited_seconds();
  if (!a.load_map.empty()) stats["load_map"] = a.load_map;
  if (a.localize) stats["localize"] = true;
  OutputFiles files = run_output_files(a.out, result, *slam, stats, nullptr, !a.no_images);
  if (!a.save_map.empty()) {
    const std::vector<std::uint8_t> map =
        encode_dsmap(own_map_snapshot(*slam, kRobotName, continued ? continued->version : 0));
    files.add(a.save_map, std::string(map.begin(), map.end()));
  }
  files.write_all();
  print_summary(result, a.out);
}

}  // namespace

void add_run_command(CLI::App& app) {
  auto args = std::make_shared<RunArgs>();
  CLI::App* cmd = app.add_subcommand("run", "Single-robot SLAM on a recorded log (CARMEN .log/.clf[.gz], ROS1 .bag, ROS 2 bag)");
  cmd->add_option("log", args->log, "Log: CARMEN file, ROS1 .bag, ROS 2 bag (folder, .db3 or .mcap)")->required();
  cmd->add_option("--out", args->out, "Output directory (created if needed)")->required();
  cmd->add_option("--scan-topic", args->scan_topic, "ROS bag: sensor_msgs/LaserScan topic")->capture_default_str();
  const CLI::Option* odom_topic =
      cmd->add_option("--odom-topic", args->odom_topic, "ROS bag: nav_msgs/Odometry topic")->capture_default_str();
  cmd->add_flag("--tf-odometry", args->tf_odometry, "ROS bag: take odometry from /tf instead of the odometry topic");
  cmd->add_option("--beams", args->beams, "CARMEN beam angles: params (# PARAM lines, else classic), classic, span180")
      ->check(CLI::IsMember({"params", "classic", "span180"}))
      ->capture_default_str();
  cmd->add_option("--laser-offset", args->laser_offset, "Laser pose on the robot: X Y THETA (m, m, rad)")
      ->expected(3);
  cmd->add_option("--save-map", args->save_map, "Write the robot's map at the end of the run (.dsmap, see README)");
  CLI::Option* load = cmd->add_option("--load-map", args->load_map,
                                      "Continue mapping in a saved map (.dsmap; layer 0, with the file's evidence model)");
  cmd->add_flag("--localize", args->localize,
               "With --load-map: localize in the map without changing it (no new evidence, no loop closing); "
               "--save-map then writes it unchanged")
      ->needs(load);
  cmd->add_option("--start-pose", args->start_pose,
                  "With --load-map: robot pose at the first scan in the map's frame, X Y THETA (m, m, rad); "
                  "default: the first scan's odometry pose")
      ->expected(3)
      ->needs(load);
  cmd->add_option("--max-scans", args->max_scans, "Process only the first N scans of the log")
      ->check(CLI::PositiveNumber);
  cmd->add_flag("--no-images", args->no_images, "Write trajectory.tum and stats.json only (no map.pgm/.yaml/.png)");
  add_slam_options(*cmd, args->slam);
  cmd->callback([args, odom_topic] {
    args->odom_topic_named = odom_topic->count() > 0;
    run(*args);
  });
}

void add_config_command(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand("config",
                                     "Print the default configuration (JSON, for --config): SLAM and swarm sections, "
                                     "as `run` uses them, or with --swarm as swarm, demo, agent and launch do");
  auto swarm = std::make_shared<bool>(false);
  cmd->add_flag("--swarm", *swarm,
                "The swarm commands' defaults: a pose-graph round every 20 nodes (run's: 40)");
  cmd->callback([swarm] {
    SwarmConfig defaults;
    if (!*swarm) defaults.slam = SlamConfig{};
    fmt::print("{}\n", to_json(defaults).dump(2));
  });
}

}  // namespace dsswarm
