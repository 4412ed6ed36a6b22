#include "agent/agent_runtime.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <limits>

#include "agent/agent_files.hpp"
#include "agent/checkpoint.hpp"
#include "common/agent_name.hpp"
#include "common/errors.hpp"
#include "common/process_usage.hpp"

namespace dsswarm::agent {
namespace {

using namespace std::chrono_literals;

AgentOptions resolved(AgentOptions o) {
  if (!is_valid_agent_name(o.name))
    throw ConfigError(fmt::format("'{}' is not a valid robot name (letters, digits, '_', '-', '.'; at most {})", o.name,
                                  kMaxAgentNameLength));
  o.swarm.validate();
  if (!(o.time_scale > 0.0)) throw ConfigError("agent: the time scale (playback rate) must be > 0");
  o.swarm.exchange_timeout *= o.time_scale;  // the same wall time on the play clock
  o.swarm.offer_timeout *= o.time_scale;
  if (!(o.heartbeat_period > 0.0) || !(o.peer_timeout > o.heartbeat_period))
    throw ConfigError("agent: the peer timeout must exceed the heartbeat period, both > 0");
  if (o.incarnation == 0)
    o.incarnation = static_cast<std::uint64_t>(
        std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch())
            .count());
  return o;
}

std::unique_ptr<SwarmAgent> make_agent(const AgentOptions& o, Executor& background, std::uint64_t& scans_before,
                                       std::optional<double>& resumed_at, Trajectory& trajectory) {
  const SlamConfig slam = agent_slam_config(o.swarm.slam, o.name);
  if (!o.resume) {
    if (const auto previous = set_aside_checkpoint(o.out))
      spdlog::warn("{}: starting afresh (no --resume): the checkpoint of the earlier run is kept in {}", o.name,
                   previous->string());
    auto agent = std::make_unique<SwarmAgent>(o.name, slam, &background);
    agent->set_merge_delay(o.swarm.merge_delay);
    return agent;
  }
  Checkpoint c = read_checkpoint(o.out, o.name);
  spdlog::info("{}: resuming from {} ({} scans, {} layers, pose {:.2f} {:.2f} {:.2f})", o.name, o.out.string(),
               c.scans_processed, c.snapshot.layers.size(), c.pose.x, c.pose.y, c.pose.theta);
  scans_before = c.scans_processed;
  if (!c.trajectory.empty()) resumed_at = c.trajectory.back().timestamp;
  trajectory = std::move(c.trajectory);
  auto agent = std::make_unique<SwarmAgent>(o.name, slam, c.snapshot, c.pose, &background, c.odometry);
  agent->set_merge_delay(o.swarm.merge_delay);
  return agent;
}

}  // namespace

AgentRuntime::AgentRuntime(AgentOptions options, ScanFeed& feed, protocol::SwarmLink& link, RobotOutputs* outputs)
    : options_(resolved(std::move(options))),
      feed_(feed),
      link_(link),
      outputs_(outputs),
      started_(SteadyClock::now()),
      gate_(options_.name, options_.limits),
      triggers_(std::chrono::milliseconds(static_cast<long>(options_.trigger_patience * 1000.0))),
      heartbeats_(options_.name, options_.incarnation) {
  Trajectory trajectory;
  shared_ = std::make_unique<SharedAgent>(make_agent(options_, loop_closing_, scans_before_, resumed_at_, trajectory),
                                          options_.swarm.encounter.locate);
  shared_->restore_trajectory(std::move(trajectory));
  if (outputs_) live_map_ = std::make_unique<LiveMapOutput>(*shared_, *outputs_);
  engine_ = std::make_unique<protocol::EncounterEngine>(options_.name, options_.swarm, *shared_, options_.incarnation);
}

AgentRuntime::~AgentRuntime() {
  if (checkpoint_writer_.joinable()) checkpoint_writer_.join();
  stop_swarm_ = true;
  link_.wake();
  if (swarm_thread_.joinable()) swarm_thread_.join();
  if (heartbeat_thread_.joinable()) heartbeat_thread_.join();
}

double AgentRuntime::now() const { return std::chrono::duration<double>(SteadyClock::now() - started_).count(); }
double AgentRuntime::swarm_now() const { return now() * options_.time_scale; }

void AgentRuntime::run(const std::atomic<bool>& stop) {
  swarm_thread_ = std::thread([this] { swarm_loop(); });
  heartbeat_thread_ = std::thread([this] { heartbeat_loop(); });
  std::optional<double> exhausted_at;
  while (!stop.load()) {
    if (std::optional<LaserScan> scan = feed_.next(100ms)) {
      // A log or simulated run played again from its start after a crash:
      // what the checkpoint holds already is not mapped a second time.
      if (resumed_at_ && scan->timestamp <= *resumed_at_) {
        ++scans_in_checkpoint_;
        continue;
      }
      install_due(scan->timestamp);
      after_scan(*scan, shared_->process(*scan));
      continue;
    }
    {
      std::lock_guard lock(trigger_mutex_);
      fire(triggers_.overdue(SteadyClock::now()));
    }
    if (!feed_.exhausted()) continue;
    install_due(std::numeric_limits<double>::infinity());  // no scan comes to wait for
    if (!exhausted_at) exhausted_at = now();
    const double idle = now() - *exhausted_at;
    const bool busy = open_encounters_.load() > 0 || shared_->composing();
    // Encounters still running may finish within one exchange time-out; one
    // still waiting then for a peer's offer (that peer may be gone or refused)
    // is recorded as abandoned.
    if (idle >= options_.linger && (!busy || idle >= options_.linger + options_.swarm.exchange_timeout)) break;
  }
  stop_swarm_ = true;
  link_.wake();
  swarm_thread_.join();
  heartbeat_thread_.join();
  {  // encounters still open are recorded as such, not lost
    std::lock_guard lock(engine_mutex_);
    engine_->abandon_all(options_.name + " stopped", swarm_now());
    flush_engine();
  }
  install_due(std::numeric_limits<double>::infinity());
  write_outputs();
}

void AgentRuntime::install_due(double stamp) {
  const std::optional<SwarmAgent::Installed> installed = shared_->install_due(stamp);
  const auto composed = shared_->take_composed();
  std::lock_guard lock(report_mutex_);
  const auto since_event = [&](std::uint64_t encounter, double at) -> std::optional<double> {
    const auto it = event_time_.find(encounter);
    return it == event_time_.end() ? std::nullopt : std::optional<double>(1000.0 * (at - it->second));
  };
  for (const auto& [encounter, at] : composed)
    if (auto ms = since_event(encounter, std::chrono::duration<double>(at - started_).count()))
      report_.merge_ready_ms.push_back(*ms);
  if (!installed) return;
  if (installed->late) ++report_.merges_late;
  for (std::uint64_t encounter : installed->encounters)
    if (auto ms = since_event(encounter, now())) report_.merge_latencies_ms.push_back(*ms);
}

void AgentRuntime::after_scan(const LaserScan& scan, const SlamStep& step) {
  const SteadyClock::time_point t = SteadyClock::now();
  ++processed_;
  {
    std::lock_guard lock(report_mutex_);
    if (last_scan_at_) {
      const double gap = std::chrono::duration<double, std::milli>(t - *last_scan_at_).count();
      report_.largest_gap_ms = std::max(report_.largest_gap_ms, gap);
      if (open_encounters_.load() > 0 || shared_->composing())
        report_.largest_gap_during_encounter_ms = std::max(report_.largest_gap_during_encounter_ms, gap);
    }
    last_scan_at_ = t;
  }
  {
    std::lock_guard lock(trigger_mutex_);
    fire(triggers_.on_scan(scan.timestamp));
    fire(triggers_.overdue(t));
  }
  if (outputs_) {
    outputs_->pose(scan.timestamp, step.pose, scan.odometry);
    live_map_->after_scan(scan.timestamp, t);
  }
  if (options_.checkpoint_period > 0.0 && now() - last_checkpoint_ >= options_.checkpoint_period) {
    last_checkpoint_ = now();
    checkpoint(false);
  }
}

// Called with trigger_mutex_ held.
void AgentRuntime::fire(std::vector<Trigger> due) {
  if (due.empty()) return;
  for (Trigger& t : due) {
    shared_->stage_view(t.peer, t.encounter);  // the view right after its scan
    if (t.late) ++triggers_late_;
    fired_.push_back(std::move(t));
  }
  link_.wake();
}

protocol::AgentStatus AgentRuntime::status(double t) const {
  protocol::AgentStatus s;
  s.uptime = t;
  s.scans_received = feed_.received();
  s.scans_processed = scans_before_ + processed_.load();
  s.scans_skipped = feed_.dropped();
  s.scans_per_second = rate_.load();
  s.encounters = decided_.load();
  s.encounters_accepted = accepted_.load();
  s.last_merge_age = last_merge_.load() >= 0.0 ? t - last_merge_.load() : -1.0;
  s.messages_rejected = messages_rejected_.load();
  shared_->with_agent([&](const SwarmAgent& a) {
    s.peers_known = static_cast<std::uint32_t>(a.knowledge().size());
    s.map_version = a.own_version();
    return 0;
  });
  return s;
}

AgentReport AgentRuntime::report() const {
  AgentReport r;
  {
    std::lock_guard lock(engine_mutex_);
    r.status = status(now());
    r.rejected_by_reason = gate_.rejected_by_reason();
    r.moved_received = moved_received_;
    r.moved_bytes_received = moved_bytes_received_;
    r.messages_deferred = sends_.deferred();
  }
  std::lock_guard lock(report_mutex_);
  r.wall_seconds = now();
  r.cpu_seconds = cpu_seconds();
  r.largest_gap_ms = report_.largest_gap_ms;
  r.largest_gap_during_encounter_ms = report_.largest_gap_during_encounter_ms;
  r.merge_latencies_ms = report_.merge_latencies_ms;
  r.merge_ready_ms = report_.merge_ready_ms;
  r.merges_late = report_.merges_late;
  r.outcomes = report_.outcomes;
  r.triggers_late = triggers_late_;
  r.scans_in_checkpoint = scans_in_checkpoint_.load();
  return r;
}

void AgentRuntime::checkpoint(bool wait) {
  // Encoding and writing a big map takes a while: off the scan path, one at a time.
  if (checkpoint_writer_.joinable()) {
    if (!wait && !checkpoint_written_) return;  // the last one is still being written: skip this round
    checkpoint_writer_.join();
  }
  Checkpoint c = shared_->with_trajectory([&](const SwarmAgent& a, const Trajectory& trajectory) {
    Checkpoint k;
    k.name = options_.name;
    k.snapshot = a.snapshot();
    k.pose = a.slam().pose();
    k.stamp = a.last_scan() ? a.last_scan()->timestamp : 0.0;
    if (a.last_scan()) k.odometry = a.last_scan()->odometry;
    k.scans_processed = scans_before_ + processed_.load();
    k.trajectory = trajectory;
    return k;
  });
  checkpoint_written_ = false;
  checkpoint_writer_ = std::thread([this, c = std::move(c)] {
    try {
      write_checkpoint(options_.out, c);
    } catch (const std::exception& e) {
      spdlog::warn("{}: checkpoint not written: {}", options_.name, e.what());
    }
    checkpoint_written_ = true;
  });
  if (wait) checkpoint_writer_.join();
}

void AgentRuntime::write_outputs() {
  shared_->finish();
  checkpoint(true);
  const AgentReport r = report();
  shared_->with_trajectory([&](const SwarmAgent& a, const Trajectory& trajectory) {
    write_agent_files(options_.out, a, trajectory, r, options_.swarm);
    return 0;
  });
}

}  // namespace dsswarm::agent
