#include "apps/agent_command.hpp"

#include <fmt/core.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <atomic>
#include <memory>
#include <thread>

#include "agent/agent_runtime.hpp"
#include "agent/paced_feed.hpp"
#include "agent/proximity_player.hpp"
#include "apps/log_input.hpp"
#include "apps/sim_swarm_run.hpp"
#include "apps/slam_options.hpp"
#include "apps/start_time.hpp"
#include "apps/stop_signal.hpp"
#include "apps/swarm_options.hpp"
#include "common/errors.hpp"
#include "io/logs/log_reader.hpp"
#include "net/ros2_input.hpp"
#include "net/ros2_output.hpp"
#include "net/swarm_link.hpp"
#include "sensor/play_clock.hpp"

namespace dsswarm {
namespace {

using namespace std::chrono_literals;

struct AgentArgs {
  std::string name;
  std::string out;
  SlamOptions slam;
  SwarmNetOptions net;
  // Input: live ROS 2 topics (default), a log, or one robot of the simulated swarm.
  std::string ns;
  std::string scan_topic = "scan", odom_topic = "odom";
  bool tf_odometry = false;
  std::string log;
  std::vector<double> range;  // from, to (s after the log's first scan)
  bool backward = false;
  std::optional<std::uint64_t> sim_seed;
  int sim_robot = 1, sim_robots = 3;
  std::uint64_t world_seed = 1;
  double proximity_range = 3.0;
  double duration = 0.0;  // s of the simulated run (0: all)
  double rate = 1.0;
  std::size_t queue = 8;  // scans waiting for SLAM; the oldest are skipped beyond
  std::optional<double> start_at;  // unix time of clock 0 (launch starts robots together)
  bool no_ros_output = false;
  bool reliable_input = false;
  bool resume = false;
  double checkpoint_period = 30.0;
  double linger = 5.0;
  double heartbeat = 1.0;
  double peer_timeout = 6.0;
};

// The live ROS-facing side: /map (merged map), tf map → odom, pose, path.
class DdsOutputs : public agent::RobotOutputs {
 public:
  DdsOutputs(net::Participant& p, const std::string& ns) : map_(p, map_config(ns)), pose_(p, pose_config(ns)) {}
  void pose(double stamp, const Pose2& map_pose, const std::optional<Pose2>& odometry) override {
    pose_.publish(stamp, map_pose, odometry);
  }
  bool map_due(agent::SteadyClock::time_point now) const override { return map_.due(now); }
  void map(GridRaster raster, double stamp) override {
    if (raster.width > 0) map_.publish(std::move(raster), stamp);
  }
  ~DdsOutputs() override { map_.flush(2s); }

 private:
  static net::MapPublisherConfig map_config(const std::string& ns) {
    net::MapPublisherConfig c;
    c.ns = ns;
    c.topic = ns.empty() ? "/map" : "map";  // per robot under its namespace, else the ROS default
    return c;
  }
  static net::PoseOutputConfig pose_config(const std::string& ns) {
    net::PoseOutputConfig c;
    c.ns = ns;
    return c;
  }
  net::MapPublisher map_;
  net::PoseOutput pose_;
};

// Live scans from ROS 2 topics.
class LiveFeed : public agent::ScanFeed {
 public:
  LiveFeed(net::Participant& p, const net::LiveInputConfig& c) : source_(p, c) {}
  std::optional<LaserScan> next(std::chrono::milliseconds timeout) override { return source_.next(timeout); }
  bool exhausted() const override { return false; }
  void wake() override { source_.wake(); }
  std::uint64_t received() const override { return source_.stats().scans_received; }
  std::uint64_t dropped() const override { return source_.stats().scans_dropped; }

 private:
  net::LiveScanSource source_;
};

// A log's segment as this robot plays it (file order, or reversed).
AgentStream log_stream(const AgentArgs& a) {
  SensorLog log = read_input_log(a.log);
  std::vector<double> clock = play_clock(log.scans);
  AgentStream s{a.name, {}, {}};
  const double from = a.range.empty() ? 0.0 : a.range[0], to = a.range.empty() ? 1e300 : a.range[1];
  for (std::size_t i = 0; i < log.scans.size(); ++i)
    if (clock[i] >= from && clock[i] <= to) s.scans.push_back(std::move(log.scans[i]));
  if (s.scans.empty()) throw ConfigError(fmt::format("--range {} {}: no scan of {} lies in it", from, to, a.log));
  if (a.backward) std::reverse(s.scans.begin(), s.scans.end());
  s.clock = play_clock(s.scans, a.backward ? PlayDirection::backward : PlayDirection::forward);
  return s;
}

// A robot of a launch that comes up after the common clock 0 has missed its
// first scans: its map starts from odometry that has drifted meanwhile.
void warn_if_late(const std::string& name, const std::optional<std::chrono::system_clock::time_point>& start_at) {
  if (!start_at) return;
  const double late = std::chrono::duration<double>(std::chrono::system_clock::now() - *start_at).count();
  if (late > 0.5)
    spdlog::warn("{}: ready {:.1f} s after clock 0 (--start-at): the scans played before are missed (counted as "
                 "skipped beyond the queue); `launch --startup` gives the robots longer",
                 name, late);
}

void check(const AgentArgs& a) {
  const int sources = (a.log.empty() ? 0 : 1) + (a.sim_seed ? 1 : 0);
  if (sources > 1) throw ConfigError("--log and --sim are alternatives: give one (or neither, for live ROS 2 topics)");
  if (!(a.rate > 0.0 && std::isfinite(a.rate))) throw ConfigError(fmt::format("--rate {} is not > 0", a.rate));
  if (!a.range.empty() && (a.range.size() != 2 || !(a.range[0] < a.range[1])))
    throw ConfigError("--range takes FROM TO (s after the log's first scan), FROM < TO");
  if ((!a.range.empty() || a.backward) && a.log.empty()) throw ConfigError("--range and --backward go with --log");
  if (a.sim_seed && (a.sim_robot < 1 || a.sim_robot > a.sim_robots))
    throw ConfigError(fmt::format("--robot {} is not one of the {} simulated robots", a.sim_robot, a.sim_robots));
}

agent::AgentOptions agent_options(const AgentArgs& a) {
  agent::AgentOptions o;
  o.name = a.name;
  o.out = a.out.empty() ? std::filesystem::path("out") / "agents" / a.name : std::filesystem::path(a.out);
  o.swarm = a.slam.resolve_swarm();
  o.resume = a.resume;
  o.checkpoint_period = a.checkpoint_period;
  o.linger = a.linger;
  o.heartbeat_period = a.heartbeat;
  o.peer_timeout = a.peer_timeout;
  if (a.sim_seed || !a.log.empty()) o.time_scale = a.rate;
  return o;
}

// What the robot maps from: a simulated robot (which also senses its own
// proximity events, into `sensed`, and sets the encounter's search radius to
// its sensor's range), a log, or live ROS 2 topics.
std::unique_ptr<agent::ScanFeed> make_feed(const AgentArgs& a, SwarmNet& net, const agent::PacedFeedConfig& paced,
                                           agent::AgentOptions& o, std::vector<agent::TimedProximity>& sensed) {
  if (a.sim_seed) {
    SimSwarmRun sim = simulate_swarm_run({a.sim_robots, *a.sim_seed, a.world_seed, a.proximity_range, a.duration});
    o.swarm.encounter.locate.search_radius = a.proximity_range;
    const std::size_t k = static_cast<std::size_t>(a.sim_robot - 1);
    if (sim.streams[k].name != a.name)
      spdlog::warn("agent {} plays simulated robot {} ('{}'); its peers know it as '{}'", a.name, a.sim_robot,
                   sim.streams[k].name, a.name);
    for (agent::TimedProximity& e : agent::proximity_schedule(sim.streams, sim.events))
      if (e.event.a == sim.streams[k].name || e.event.b == sim.streams[k].name) sensed.push_back(std::move(e));
    return std::make_unique<agent::PacedFeed>(sim.streams[k].scans, sim.streams[k].clock, paced);
  }
  if (!a.log.empty()) {
    AgentStream s = log_stream(a);
    return std::make_unique<agent::PacedFeed>(std::move(s.scans), std::move(s.clock), paced);
  }
  net::LiveInputConfig live;
  live.ns = a.ns;
  live.scan_topic = a.scan_topic;
  live.odom_topic = a.odom_topic;
  live.odometry = a.tf_odometry ? net::OdometrySource::kTf : net::OdometrySource::kTopic;
  live.queue_capacity = a.queue;
  live.reliable = a.reliable_input;
  return std::make_unique<LiveFeed>(net.ros(), live);
}

void run_agent(const AgentArgs& a) {
  check(a);
  agent::AgentOptions o = agent_options(a);
  const StopOnSignal stop_on_signal;
  SwarmNet net(a.net, a.name);
  std::vector<agent::TimedProximity> sensed;  // a simulated robot's own proximity sensor
  const auto start_at = start_time(a.start_at);
  const agent::PacedFeedConfig paced{.rate = a.rate, .queue_capacity = a.queue, .start_at = start_at};
  const std::unique_ptr<agent::ScanFeed> feed = make_feed(a, net, paced, o, sensed);
  std::unique_ptr<DdsOutputs> outputs;
  if (!a.no_ros_output) outputs = std::make_unique<DdsOutputs>(net.ros(), a.ns);
  agent::AgentRuntime runtime(o, *feed, net.link(), outputs.get());
  std::unique_ptr<agent::ProximityPlayer> sensor;
  if (!sensed.empty())
    sensor = std::make_unique<agent::ProximityPlayer>(std::move(sensed), a.rate, 1.0, start_at,
                                                      [&](const protocol::Proximity& e) { runtime.raise_proximity(e); });
  spdlog::info("{}: running ({}); outputs in {}", a.name,
               a.sim_seed ? fmt::format("simulated robot {}", a.sim_robot)
               : a.log.empty() ? fmt::format("ROS 2 topics under '{}'", a.ns.empty() ? "/" : a.ns)
                               : a.log,
               o.out.string());
  // The swarm participant's upkeep (lost security handshakes), beside the runtime.
  std::atomic<bool> finished{false};
  std::thread upkeep([&] {
    while (!finished) {
      for (int i = 0; i < 10 && !finished; ++i) std::this_thread::sleep_for(100ms);
      if (!finished) net.maintain();
    }
  });
  warn_if_late(a.name, start_at);
  runtime.run(StopOnSignal::requested());
  finished = true;
  upkeep.join();
  const agent::AgentReport r = runtime.report();
  fmt::print("{}: {} scans processed, {} skipped; {} encounters, {} accepted; {} messages refused; outputs in {}\n",
             a.name, r.status.scans_processed, r.status.scans_skipped, r.status.encounters,
             r.status.encounters_accepted, r.status.messages_rejected, o.out.string());
}

}  // namespace

void add_agent_command(CLI::App& app) {
  auto args = std::make_shared<AgentArgs>();
  CLI::App* cmd = app.add_subcommand(
      "agent", "Run one robot of the swarm: SLAM on live ROS 2 topics (or a log, or a simulated robot), encounters "
               "with peers over DDS, /map out");
  cmd->add_option("--name", args->name, "This robot's name in the swarm")->required();
  cmd->add_option("--out", args->out, "Outputs and checkpoints (default out/agents/NAME)");
  cmd->add_option("--namespace", args->ns, "ROS namespace of the robot's topics, e.g. /robot1");
  cmd->add_option("--scan-topic", args->scan_topic, "sensor_msgs/LaserScan topic (relative to the namespace)")
      ->capture_default_str();
  cmd->add_option("--odom-topic", args->odom_topic, "nav_msgs/Odometry topic")->capture_default_str();
  cmd->add_flag("--tf-odometry", args->tf_odometry, "Odometry from /tf (odom -> base_link) instead");
  cmd->add_option("--log", args->log, "Play this log instead of live topics (CARMEN, ROS1 or ROS 2 bag)");
  cmd->add_option("--range", args->range, "With --log: FROM TO, seconds after the log's first scan")->expected(2);
  cmd->add_flag("--backward", args->backward, "With --log: play the segment last scan first");
  cmd->add_option("--sim", args->sim_seed, "Play a robot of the built-in simulated swarm (this run seed)");
  cmd->add_option("--robot", args->sim_robot, "With --sim: which robot (1..N)")->capture_default_str();
  cmd->add_option("--robots", args->sim_robots, "With --sim: robots in the simulated swarm")->capture_default_str();
  cmd->add_option("--world-seed", args->world_seed, "With --sim: seed of the generated building")->capture_default_str();
  cmd->add_option("--proximity-range", args->proximity_range, "With --sim: proximity sensor range (m)")
      ->capture_default_str();
  cmd->add_option("--duration", args->duration, "With --sim: seconds of the simulated run to play (0: all of it)")
      ->capture_default_str();
  cmd->add_option("--rate", args->rate, "With --log/--sim: playback speed factor")->capture_default_str();
  cmd->add_option("--queue", args->queue, "Scans that may wait for SLAM; beyond, the oldest are skipped (counted)")
      ->check(CLI::Range(std::size_t{1}, std::size_t{10000}))
      ->capture_default_str();
  cmd->add_option("--start-at", args->start_at, "With --log/--sim: unix time at which playback starts");
  cmd->add_flag("--no-ros-output", args->no_ros_output, "Do not publish /map, /tf, pose and path");
  cmd->add_flag("--reliable-input", args->reliable_input,
                "Read scan and odometry reliably (no sample lost under load; matches only reliable publishers "
                "such as `dsswarm replay`, not SensorDataQoS lidar drivers)");
  cmd->add_flag("--resume", args->resume, "Continue from the checkpoint in --out (after a crash)");
  cmd->add_option("--checkpoint-period", args->checkpoint_period, "Seconds between checkpoints (0: only at exit)")
      ->capture_default_str();
  cmd->add_option("--linger", args->linger, "With --log/--sim: seconds to keep answering peers at the end")
      ->capture_default_str();
  cmd->add_option("--heartbeat", args->heartbeat, "Seconds between heartbeats")->capture_default_str();
  cmd->add_option("--peer-timeout", args->peer_timeout, "Seconds without a heartbeat before a peer counts as gone")
      ->capture_default_str();
  add_swarm_net_options(*cmd, args->net);
  add_slam_options(*cmd, args->slam);
  cmd->callback([args] { run_agent(*args); });
}

}  // namespace dsswarm
