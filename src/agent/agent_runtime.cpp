#include "agent/agent_runtime.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <set>

#include "agent/agent_files.hpp"
#include "agent/checkpoint.hpp"
#include "common/agent_name.hpp"
#include "common/errors.hpp"
#include "common/process_usage.hpp"

namespace dsswarm::agent {
namespace {

using namespace std::chrono_literals;

// Messages held for one encounter whose scan has not come yet: an offer and a
// placement at most in a well-behaved exchange.
constexpr std::size_t kMaxHeldPerEncounter = 64;

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
    return std::make_unique<SwarmAgent>(o.name, slam, &background);
  }
  Checkpoint c = read_checkpoint(o.out, o.name);
  spdlog::info("{}: resuming from {} ({} scans, {} layers, pose {:.2f} {:.2f} {:.2f})", o.name, o.out.string(),
               c.scans_processed, c.snapshot.layers.size(), c.pose.x, c.pose.y, c.pose.theta);
  scans_before = c.scans_processed;
  if (!c.trajectory.empty()) resumed_at = c.trajectory.back().timestamp;
  trajectory = std::move(c.trajectory);
  return std::make_unique<SwarmAgent>(o.name, slam, c.snapshot, c.pose, &background, c.odometry);
}

std::uint64_t encounter_of(const protocol::Body& body) {
  if (const auto* o = std::get_if<protocol::Offer>(&body)) return o->encounter;
  if (const auto* p = std::get_if<protocol::Placement>(&body)) return p->encounter;
  if (const auto* c = std::get_if<protocol::Chunk>(&body)) return c->encounter;
  if (const auto* d = std::get_if<protocol::Decline>(&body)) return d->encounter;
  return 0;
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
      after_scan(*scan, shared_->process(*scan));
      continue;
    }
    for (std::uint64_t id : shared_->install_ready()) note_installed(id);
    {
      std::lock_guard lock(trigger_mutex_);
      fire(triggers_.overdue(SteadyClock::now()));
    }
    if (!feed_.exhausted()) continue;
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
  for (std::uint64_t id : shared_->install_ready()) note_installed(id);
  write_outputs();
}

void AgentRuntime::note_installed(std::uint64_t encounter) {
  std::lock_guard lock(report_mutex_);
  if (auto it = event_time_.find(encounter); it != event_time_.end())
    report_.merge_latencies_ms.push_back(1000.0 * (now() - it->second));
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
  for (std::uint64_t id : shared_->install_ready()) note_installed(id);
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

void AgentRuntime::swarm_loop() {
  while (!stop_swarm_.load()) {
    std::vector<std::vector<std::uint8_t>> arrived = link_.receive(50ms);
    const double t = swarm_now();
    // Peers are judged by what had arrived by now: handling this batch may
    // take a while (placing a peer's scan), and their heartbeats wait meanwhile.
    const double received_at = now();
    std::lock_guard lock(engine_mutex_);
    for (const std::vector<std::uint8_t>& bytes : arrived) {
      protocol::MessageGate::Verdict v = gate_.admit(bytes);
      if (!v.rejected.empty()) ++messages_rejected_;
      if (!v.rejected.empty()) warnings_.note(fmt::format("{}: message refused: {}", options_.name, v.rejected));
      if (!v.message) continue;
      if (v.peer_restarted) engine_->drop_peer(v.message->header.sender, v.message->header.sender + " restarted", t);
      handle(*v.message, bytes.size(), t);
    }
    std::vector<Trigger> fired;
    {
      std::lock_guard tl(trigger_mutex_);
      fired.swap(fired_);
    }
    for (const Trigger& f : fired) start_encounter(f.peer, f.encounter, t);
    engine_->tick(t);
    drop_silent_peers(received_at);
    flush_engine();
  }
}

void AgentRuntime::handle(const protocol::Message& m, std::size_t bytes, double t) {
  const std::string& from = m.header.sender;
  if (const auto* h = std::get_if<protocol::Heartbeat>(&m.body)) {
    peers_[from] = Peer{h->status, now(), false};  // (≥ received_at: it was in the batch)
    return;
  }
  if (const auto* p = std::get_if<protocol::Proximity>(&m.body)) {
    on_proximity(*p, t);
    return;
  }
  if (std::holds_alternative<protocol::Moved>(m.body)) {
    ++moved_received_;
    moved_bytes_received_ += bytes;
  }
  const std::uint64_t id = encounter_of(m.body);
  {
    std::lock_guard tl(trigger_mutex_);
    if (triggers_.armed(from, id)) {  // our view is not taken yet: it waits for its scan
      auto& held = held_[{from, id}];
      if (held.size() < kMaxHeldPerEncounter) held.emplace_back(m, bytes);  // beyond: the exchange times out
      return;
    }
  }
  engine_->receive(m, bytes, t);
}

bool AgentRuntime::arm_unless_now(const protocol::Proximity& p) {
  if (p.a != options_.name && p.b != options_.name) return true;
  const bool am_a = p.a == options_.name;
  const double stamp = am_a ? p.a_stamp : p.b_stamp;
  if (std::isnan(stamp)) return false;
  std::lock_guard tl(trigger_mutex_);
  fire(triggers_.arm({am_a ? p.b : p.a, p.event, stamp, SteadyClock::now(), false}));
  return true;
}

void AgentRuntime::on_proximity(const protocol::Proximity& p, double t) {
  if (!arm_unless_now(p)) start_encounter(p.a == options_.name ? p.b : p.a, p.event, t);
}

void AgentRuntime::raise_proximity(const protocol::Proximity& p) {
  // A stamped event only arms a trigger: it must not wait for the engine,
  // which the swarm thread holds while it places a peer's scan (seconds): the
  // scan the event names would pass meanwhile and the robot join late, from
  // another view than the in-process swarm's.
  if (arm_unless_now(p)) return;
  std::lock_guard lock(engine_mutex_);
  on_proximity(p, swarm_now());
}

void AgentRuntime::start_encounter(const std::string& peer, std::uint64_t id, double t) {
  {
    std::lock_guard lock(report_mutex_);
    event_time_.emplace(id, now());  // wall time: latencies are the robot's
  }
  engine_->start(peer, id, t);
  if (auto it = held_.find({peer, id}); it != held_.end()) {
    for (const auto& [message, bytes] : it->second) engine_->receive(message, bytes, t);
    held_.erase(it);
  }
}

void AgentRuntime::flush_engine() {
  std::set<std::string> unreachable;
  for (const protocol::Outgoing& out : engine_->take_outbox())
    if (!unreachable.contains(out.recipient) && !link_.send(out.recipient, out.bytes)) unreachable.insert(out.recipient);
  // An exchange that lost a message cannot finish: end it now rather than
  // hold a slot until it times out.
  for (const std::string& peer : unreachable)
    engine_->drop_peer(peer, fmt::format("{} cannot be reached: a message to it was not delivered (gone, or not authorized)", peer),
                       swarm_now());
  for (protocol::EncounterOutcome& o : engine_->take_outcomes()) {
    using End = protocol::EncounterOutcome::End;
    if (o.end == End::accepted || o.end == End::rejected) ++decided_;
    if (o.end == End::accepted) {
      ++accepted_;
      last_merge_ = now();
    }
    spdlog::info("{}: encounter {} with {}: {}{}", options_.name, o.encounter, o.peer,
                 o.end == End::accepted ? "accepted" : "not merged", o.reason.empty() ? "" : " (" + o.reason + ")");
    std::lock_guard lock(report_mutex_);
    report_.outcomes.push_back(std::move(o));
  }
  open_encounters_ = engine_->open_encounters();
}

void AgentRuntime::drop_silent_peers(double wall) {
  for (auto& [name, peer] : peers_) {
    if (peer.lost || wall - peer.last_heard <= options_.peer_timeout) continue;
    peer.lost = true;
    engine_->drop_peer(name, fmt::format("no heartbeat from {} for {:.0f} s", name, options_.peer_timeout),
                       swarm_now());
  }
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

void AgentRuntime::heartbeat_loop() {
  const auto period = std::chrono::duration<double>(options_.heartbeat_period);
  std::uint64_t processed_before = processed_.load();
  auto last = SteadyClock::now();
  while (!stop_swarm_.load()) {
    const protocol::Message m = heartbeats_.stamp("", protocol::Heartbeat{status(now())});
    link_.send("", protocol::encode(m));
    const auto wake = last + std::chrono::duration_cast<SteadyClock::duration>(period);
    while (!stop_swarm_.load() && SteadyClock::now() < wake) std::this_thread::sleep_for(10ms);
    const auto t = SteadyClock::now();
    const std::uint64_t processed = processed_.load();
    rate_ = static_cast<double>(processed - processed_before) / std::chrono::duration<double>(t - last).count();
    processed_before = processed;
    last = t;
  }
}

AgentReport AgentRuntime::report() const {
  AgentReport r;
  {
    std::lock_guard lock(engine_mutex_);
    r.status = status(now());
    r.rejected_by_reason = gate_.rejected_by_reason();
    r.moved_received = moved_received_;
    r.moved_bytes_received = moved_bytes_received_;
  }
  std::lock_guard lock(report_mutex_);
  r.wall_seconds = now();
  r.cpu_seconds = cpu_seconds();
  r.largest_gap_ms = report_.largest_gap_ms;
  r.largest_gap_during_encounter_ms = report_.largest_gap_during_encounter_ms;
  r.merge_latencies_ms = report_.merge_latencies_ms;
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
