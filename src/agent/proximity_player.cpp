#include "agent/proximity_player.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "agent/paced_feed.hpp"

namespace dsswarm::agent {

namespace {

double last_stamp_by(const AgentStream& s, double time) {
  // The session plays scan i once every event with time < clock[i] has run.
  const auto it = std::upper_bound(s.clock.begin(), s.clock.end(), time);
  if (it == s.clock.begin()) return std::numeric_limits<double>::quiet_NaN();
  return s.scans[static_cast<std::size_t>(it - s.clock.begin()) - 1].timestamp;
}

}  // namespace

std::vector<TimedProximity> proximity_schedule(const std::vector<AgentStream>& streams,
                                               std::vector<EncounterEvent> events) {
  std::stable_sort(events.begin(), events.end(),
                   [](const EncounterEvent& x, const EncounterEvent& y) { return x.time < y.time; });
  std::vector<TimedProximity> out;
  for (std::size_t i = 0; i < events.size(); ++i) {
    const EncounterEvent& e = events[i];
    const AgentStream& a = streams.at(e.a);
    const AgentStream& b = streams.at(e.b);
    out.push_back({e.time, protocol::Proximity{a.name, b.name, i, last_stamp_by(a, e.time), last_stamp_by(b, e.time)}});
  }
  return out;
}

ProximityPlayer::ProximityPlayer(std::vector<TimedProximity> events, double rate, double lead,
                                 std::optional<std::chrono::system_clock::time_point> start_at, Raise raise) {
  if (!(rate > 0.0) || !(lead >= 0.0)) throw std::invalid_argument("ProximityPlayer: rate > 0 and lead >= 0");
  const auto start = steady_start(start_at);
  const auto begun = std::chrono::steady_clock::now();
  thread_ = std::thread([this, events = std::move(events), rate, lead, start, begun, raise = std::move(raise)] {
    auto at = [&](double seconds) {
      return start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(seconds));
    };
    for (const TimedProximity& e : events) {
      if (at(e.time / rate + lead) < begun) {  // over before we started (a robot restarted mid-run)
        ++skipped_;
        continue;
      }
      const auto due = at(std::max(0.0, e.time / rate - lead));
      while (!stop_ && std::chrono::steady_clock::now() < due) std::this_thread::sleep_for(std::chrono::milliseconds(10));
      if (stop_) break;
      raise(e.event);
    }
    done_ = true;
  });
}

ProximityPlayer::~ProximityPlayer() {
  stop_ = true;
  thread_.join();
}

void ProximityPlayer::wait() {
  while (!done_) std::this_thread::sleep_for(std::chrono::milliseconds(20));
}

}  // namespace dsswarm::agent
