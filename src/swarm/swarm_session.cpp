#include "swarm/swarm_session.hpp"

#include <algorithm>
#include <chrono>
#include <limits>

#include "common/errors.hpp"

namespace dsswarm {

void SwarmConfig::validate() const {
  slam.validate();
  encounter.validate();
  if (!(remerge_interval >= 0.0)) throw ConfigError("swarm.remerge_interval must be >= 0 s");
  if (!(confirm_xy > 0.0) || !(confirm_theta > 0.0)) throw ConfigError("swarm.confirm_xy and confirm_theta must be > 0");
}

SwarmSession::SwarmSession(std::vector<AgentStream> streams, std::vector<EncounterEvent> events,
                           const SwarmConfig& config, SnapshotTransport transport)
    : streams_(std::move(streams)), events_(std::move(events)), config_(config), transport_(std::move(transport)) {
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
    SlamConfig slam = config_.slam;
    slam.seed = config_.slam.seed + 1000 * i;  // independent random streams, still reproducible
    agents_.push_back(std::make_unique<SwarmAgent>(s.name, slam));
  }
  for (const EncounterEvent& e : events_)
    if (e.a >= streams_.size() || e.b >= streams_.size() || e.a == e.b)
      throw ConfigError("an encounter names agents " + std::to_string(e.a) + " and " + std::to_string(e.b) +
                        ", but there are " + std::to_string(streams_.size()) + " agents");
  std::stable_sort(events_.begin(), events_.end(),
                   [](const EncounterEvent& x, const EncounterEvent& y) { return x.time < y.time; });
  tracks_.resize(streams_.size());
  last_merge_.assign(streams_.size(), std::vector<double>(streams_.size(), -std::numeric_limits<double>::infinity()));
  unconfirmed_.assign(streams_.size(), std::vector<std::vector<Pose2>>(streams_.size()));
}

void SwarmSession::run(const std::function<void(std::size_t, std::size_t)>& progress) {
  std::size_t total = 0, done = 0;
  for (const AgentStream& s : streams_) total += s.scans.size();
  std::vector<std::size_t> next(streams_.size(), 0);
  std::size_t next_event = 0;
  const std::size_t report_every = std::max<std::size_t>(1, total / 20);
  for (;;) {
    // The earliest pending scan over all agents; events due before it run first.
    std::size_t who = streams_.size();
    double when = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < streams_.size(); ++i)
      if (next[i] < streams_[i].scans.size() && streams_[i].clock[next[i]] < when) {
        when = streams_[i].clock[next[i]];
        who = i;
      }
    while (next_event < events_.size() && events_[next_event].time < when) encounter(events_[next_event++]);
    if (who == streams_.size()) break;
    const LaserScan& scan = streams_[who].scans[next[who]++];
    tracks_[who].timestamps.push_back(scan.timestamp);
    AgentTrack& track = tracks_[who];
    track.steps.push_back(agents_[who]->process(scan));
    for (const PoseRevision& r : track.steps.back().revised) track.steps[r.index].pose = r.pose;
    if (progress && ++done % report_every == 0) progress(done, total);
  }
  if (progress) progress(total, total);
}

void SwarmSession::encounter(const EncounterEvent& e) {
  SwarmAgent& a = *agents_[e.a];
  SwarmAgent& b = *agents_[e.b];
  if (!config_.merge || tracks_[e.a].steps.empty() || tracks_[e.b].steps.empty()) {
    ++skipped_;  // one of them has not started yet: nothing to exchange
    return;
  }
  if (e.time - last_merge_[e.a][e.b] < config_.remerge_interval) {
    ++skipped_;
    return;
  }
  using Clock = std::chrono::steady_clock;
  EncounterRecord r;
  r.time = e.time;
  r.a = a.name();
  r.b = b.name();
  r.a_log_time = tracks_[e.a].timestamps.back();
  r.b_log_time = tracks_[e.b].timestamps.back();
  // The exchange: each sends its snapshot and current scan.
  MapSnapshot from_a = a.snapshot(), from_b = b.snapshot();
  const EncounterView view_a = a.view(config_.encounter.locate), view_b = b.view(config_.encounter.locate);
  r.a_pose_in_a = view_a.pose;
  r.b_pose_in_b = view_b.pose;
  // x, y per point, both ways: scans and surroundings.
  r.bytes = 2 * sizeof(float) *
            (view_a.points.size() + view_b.points.size() + view_a.surroundings.size() + view_b.surroundings.size() +
             view_a.wide_surroundings.size() + view_b.wide_surroundings.size());
  if (transport_) {
    from_a = transport_(from_a, r.bytes);
    from_b = transport_(from_b, r.bytes);
  }
  const auto t0 = Clock::now();
  r.estimate = estimate_encounter(view_a, view_b, config_.encounter, config_.slam.seed + 77 * records_.size());
  const auto t1 = Clock::now();
  r.match_ms = std::chrono::duration<double, std::milli>(t1 - t0).count();
  r.accepted = r.estimate.accepted;
  r.reason = r.estimate.reason;
  if (r.accepted && config_.confirm) {
    const Pose2 t = r.estimate.b_frame_in_a;
    auto agrees = [&](const Pose2& other) {
      const Pose2 d = between(other * view_b.pose, t * view_b.pose);
      return std::hypot(d.x, d.y) <= config_.confirm_xy && std::abs(normalize_angle(d.theta)) <= config_.confirm_theta;
    };
    std::vector<Pose2>& pending = unconfirmed_[std::min(e.a, e.b)][std::max(e.a, e.b)];
    // Stored as b's frame in a's for the pair's lower index first.
    auto stored = [&](const Pose2& p) { return e.a < e.b ? p : p.inverse(); };
    if (const MapLayer* known = a.knowledge().find(b.name()); known && agrees(known->origin_in_holder)) {
      r.confirmed_by = "known transform";
    } else {
      for (const Pose2& p : pending)
        if (agrees(stored(p))) r.confirmed_by = "earlier encounter";
    }
    if (r.confirmed_by.empty()) {
      pending.push_back(stored(t));
      r.accepted = false;
      r.reason = "unconfirmed: the placement verified, merging waits for a second encounter that agrees";
    }
  }
  if (r.accepted) {
    r.b_frame_in_a = r.estimate.b_frame_in_a;
    a.merge(from_b, r.b_frame_in_a);
    b.merge(from_a, r.b_frame_in_a.inverse());
    r.merge_ms = std::chrono::duration<double, std::milli>(Clock::now() - t1).count();
    last_merge_[e.a][e.b] = last_merge_[e.b][e.a] = e.time;
  }
  records_.push_back(std::move(r));
}

}  // namespace dsswarm
