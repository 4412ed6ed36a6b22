#include "protocol/swarm_session.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>

#include "common/errors.hpp"
#include "protocol/gate.hpp"

namespace dsswarm {

namespace {

// Why an event did not become an encounter, in words that group alike events.
std::string skip_reason(const protocol::EncounterOutcome& x, const protocol::EncounterOutcome& y,
                        const SwarmConfig& config) {
  using D = protocol::EncounterOutcome::Decline;
  const bool x_new = x.decline == D::no_scan, y_new = y.decline == D::no_scan;
  if (x_new && y_new) return fmt::format("{} and {} had not started", x.self, y.self);
  if (x_new || y_new) return fmt::format("{} had not started", x_new ? x.self : y.self);
  if (x.decline == D::merging_off || y.decline == D::merging_off) return "merging is off";
  if (x.decline == D::merged_recently || y.decline == D::merged_recently)
    return fmt::format("{} and {} merged less than {} s before", x.self, y.self, config.remerge_interval);
  if (x.decline == D::unchanged || y.decline == D::unchanged)
    return fmt::format("{} and {} had neither moved nor mapped since their last encounter", x.self, y.self);
  return x.decline != D::by_peer ? x.reason : y.reason;
}

}  // namespace

struct SwarmSession::Robot {
  // A SwarmAgent as the protocol sees it. Nothing else touches the agent while
  // an encounter runs, so its live map can be lent out without a copy.
  class Port : public protocol::AgentPort {
   public:
    Port(SwarmAgent& agent, const RelativePoseConfig& locate) : agent_(agent), locate_(locate) {}

    std::optional<protocol::CapturedView> capture_view(const std::string&, std::uint64_t) override {
      if (!agent_.last_scan()) return std::nullopt;
      protocol::CapturedView v{agent_.view(locate_), agent_.last_scan()->timestamp, nullptr, nullptr, 0, nullptr};
      // A merge not yet in use is placed in already (as a robot process does).
      if (auto fresher = agent_.fresher_placement_map()) {
        v.view.map = fresher.get();
        v.keep_alive = std::move(fresher);
      }
      return v;
    }
    MapSnapshot snapshot(const protocol::CapturedView&) override { return agent_.snapshot(); }  // nothing moved on
    std::vector<LayerVersion> inventory() const override { return agent_.inventory(); }
    std::optional<Pose2> known_frame(const std::string& origin) const override {
      const MapLayer* l = agent_.knowledge().find(origin);
      return l ? std::optional<Pose2>(l->origin_in_holder) : std::nullopt;
    }
    void merge(MapSnapshot snapshot, const Pose2& sender_in_self, const protocol::CapturedView& at,
               std::uint64_t encounter) override {
      agent_.tie(snapshot.sender, at.view.scan_index, at.view.pose, sender_in_self, encounter);
      if (agent_.absorb(snapshot, sender_in_self)) agent_.schedule_merge(encounter, at.stamp);
    }
    std::uint64_t graph_revision() const override { return agent_.graph_revision(); }
    MapMoves map_moves(const std::string& peer, const std::vector<TieScan>& ties,
                       std::size_t max_closures) const override {
      return agent_.moves(peer, ties, max_closures);
    }
    void follow(const std::string& peer, const MapMoves& moves) override { agent_.follow(peer, moves); }

   private:
    SwarmAgent& agent_;
    const RelativePoseConfig& locate_;
  };

  Robot(SwarmAgent& agent, const SwarmConfig& config)
      : port(agent, config.encounter.locate), engine(agent.name(), config, port), gate(agent.name()) {}
  Port port;
  protocol::EncounterEngine engine;
  protocol::MessageGate gate;
};

EncounterRecord make_record(const protocol::EncounterOutcome& a, const protocol::EncounterOutcome& b, double time) {
  EncounterRecord r;
  r.id = a.encounter;
  r.time = time;
  r.a = a.self;
  r.b = b.self;
  r.accepted = a.end == protocol::EncounterOutcome::End::accepted;
  r.reason = a.reason;
  r.confirmed_by = a.confirmed_by;
  r.estimate = a.estimate;
  if (r.accepted) r.b_frame_in_a = a.estimate.b_frame_in_a;
  r.a_pose_in_a = a.self_pose;
  r.b_pose_in_b = b.self_pose;
  r.a_log_time = a.self_stamp;
  r.b_log_time = b.self_stamp;
  r.match_ms = a.compute_ms + b.compute_ms;
  r.merge_ms = a.merge_ms + b.merge_ms;
  r.bytes = a.bytes_sent + a.bytes_received;
  r.snapshot_bytes = a.snapshot_bytes_sent + a.snapshot_bytes_received;
  return r;
}

SwarmSession::SwarmSession(std::vector<AgentStream> streams, std::vector<EncounterEvent> events,
                           const SwarmConfig& config)
    : streams_(std::move(streams)), events_(std::move(events)), config_(config) {
  config_.validate();
  if (streams_.empty()) throw ConfigError("a swarm needs at least one agent");
  for (std::size_t i = 0; i < streams_.size(); ++i) {
    const AgentStream& s = streams_[i];
    if (s.clock.size() != s.scans.size())
      throw ConfigError("agent " + s.name + ": one clock time per scan is needed");
    if (!std::is_sorted(s.clock.begin(), s.clock.end()))
      throw ConfigError("agent " + s.name + ": the session clock must not run backwards");
    for (std::size_t j = 0; j < i; ++j)
      if (streams_[j].name == s.name) throw ConfigError("two agents are named " + s.name);
    agents_.push_back(std::make_unique<SwarmAgent>(s.name, agent_slam_config(config_.slam, s.name)));
    agents_.back()->set_merge_delay(config_.merge_delay);
  }
  for (auto& agent : agents_) robots_.push_back(std::make_unique<Robot>(*agent, config_));
  for (const EncounterEvent& e : events_)
    if (e.a >= streams_.size() || e.b >= streams_.size() || e.a == e.b)
      throw ConfigError("an encounter names agents " + std::to_string(e.a) + " and " + std::to_string(e.b) +
                        ", but there are " + std::to_string(streams_.size()) + " agents");
  std::stable_sort(events_.begin(), events_.end(),
                   [](const EncounterEvent& x, const EncounterEvent& y) { return x.time < y.time; });
  tracks_.resize(streams_.size());
}

SwarmSession::~SwarmSession() = default;

void SwarmSession::run(const std::function<void(std::size_t, std::size_t)>& progress) {
  std::size_t total = 0, done = 0;
  for (const AgentStream& s : streams_) total += s.scans.size();
  std::vector<std::size_t> next(streams_.size(), 0);
  std::size_t next_event = 0;
  const std::size_t report_every = std::max<std::size_t>(1, total / 20);
  double end = 0.0;  // the clock of the last scan
  for (;;) {
    // The earliest pending scan over all agents; events due before it run first.
    std::size_t who = streams_.size();
    double when = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < streams_.size(); ++i)
      if (next[i] < streams_[i].scans.size() && streams_[i].clock[next[i]] < when) {
        when = streams_[i].clock[next[i]];
        who = i;
      }
    while (next_event < events_.size() && events_[next_event].time < when) {
      encounter(events_[next_event], next_event);
      ++next_event;
    }
    if (who == streams_.size()) break;
    const LaserScan& scan = streams_[who].scans[next[who]++];
    tracks_[who].timestamps.push_back(scan.timestamp);
    AgentTrack& track = tracks_[who];
    agents_[who]->install_due(scan.timestamp, true);
    track.steps.push_back(agents_[who]->process(scan));
    track.map_versions.push_back(agents_[who]->own_version());
    for (const PoseRevision& r : track.steps.back().revised) track.steps[r.index].pose = r.pose;
    robots_[who]->engine.announce_moves(when);
    pump(when);
    end = when;
    if (progress && ++done % report_every == 0) progress(done, total);
  }
  // Every robot's last round, then the others' last word on where that left
  // their maps, the robots' turns after the logs end, and a round more that
  // follows it.
  for (auto& a : agents_) {
    a->install_due(std::numeric_limits<double>::infinity(), true);
    a->finish(false);
  }
  for (auto& r : robots_) r->engine.announce_moves(end, true);
  pump(end);
  final_exchanges(end);
  // The poses as loop closing last optimized them, like `run` writes.
  for (std::size_t i = 0; i < agents_.size(); ++i) {
    agents_[i]->finish();
    const std::vector<Pose2> optimized = agents_[i]->slam().trajectory();
    for (std::size_t k = 0; k < optimized.size() && k < tracks_[i].steps.size(); ++k)
      tracks_[i].steps[k].pose = optimized[k];
  }
  if (progress) progress(total, total);
}

// Turn by turn (swarm_config.hpp, final_exchanges): each robot's last round
// sees where the robots before it just left their maps.
void SwarmSession::final_exchanges(double end) {
  for (int k = 0; k < config_.final_exchanges; ++k)
    for (std::size_t i = 0; i < agents_.size(); ++i) {
      agents_[i]->finish(false);
      robots_[i]->engine.announce_moves(end, true);
      pump(end);
    }
}

void SwarmSession::pump(double now) {
  for (bool moved = true; moved;) {
    moved = false;
    for (auto& from : robots_)
      for (protocol::Outgoing& out : from->engine.take_outbox()) {
        moved = true;
        for (auto& to : robots_) {
          if (to->engine.self() != out.recipient) continue;
          protocol::MessageGate::Verdict v = to->gate.admit(out.bytes);
          if (!v.message) continue;
          if (std::holds_alternative<protocol::Moved>(v.message->body)) {
            ++moved_messages_;
            moved_bytes_ += out.bytes.size();
          }
          to->engine.receive(*v.message, out.bytes.size(), now);
        }
      }
  }
}

void SwarmSession::encounter(const EncounterEvent& e, std::uint64_t id) {
  Robot& x = *robots_[e.a];
  Robot& y = *robots_[e.b];
  x.engine.start(y.engine.self(), id, e.time);
  y.engine.start(x.engine.self(), id, e.time);
  pump(e.time);
  // In memory the exchange completes at once; nothing may stay open.
  const protocol::EncounterOutcome *ox = nullptr, *oy = nullptr;
  std::vector<protocol::EncounterOutcome> xs = x.engine.take_outcomes(), ys = y.engine.take_outcomes();
  for (const auto& o : xs)
    if (o.encounter == id) ox = &o;
  for (const auto& o : ys)
    if (o.encounter == id) oy = &o;
  if (!ox || !oy || x.engine.open_encounters() + y.engine.open_encounters() > 0)
    throw std::logic_error("in-process encounter " + std::to_string(id) + " did not complete");
  using End = protocol::EncounterOutcome::End;
  if (ox->end == End::declined || oy->end == End::declined) {
    skipped_.push_back(skip_reason(*ox, *oy, config_));
    return;
  }
  records_.push_back(ox->self_is_a ? make_record(*ox, *oy, e.time) : make_record(*oy, *ox, e.time));
}

}  // namespace dsswarm
