#include "apps/swarm_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <map>
#include <utility>

namespace dsswarm {
namespace {

// Why the session skipped event `e` (the same tests, in the same order, as
// SwarmSession::encounter): an agent had no scan yet, merging is off, or the
// pair merged within remerge_interval.
std::string skip_reason(const EncounterEvent& e, const std::vector<std::string>& names,
                        const std::vector<double>& first_clock, double last_merge, const SwarmConfig& config) {
  if (!config.merge) return "merging is off";
  // A scan at the event's very time plays first.
  const bool a_late = first_clock[e.a] > e.time, b_late = first_clock[e.b] > e.time;
  if (a_late && b_late) return fmt::format("{} and {} had not started", names[e.a], names[e.b]);
  if (a_late || b_late) return fmt::format("{} had not started", names[a_late ? e.a : e.b]);
  if (e.time - last_merge < config.remerge_interval)
    return fmt::format("{} and {} merged less than {} s before", names[e.a], names[e.b], config.remerge_interval);
  return "not run";
}

}  // namespace

std::string describe_encounter_events(const std::string& what, const std::vector<EncounterEvent>& events,
                                      const std::vector<std::string>& names, const std::vector<double>& first_clock,
                                      const std::vector<EncounterRecord>& records, const SwarmConfig& config) {
  std::vector<EncounterEvent> order = events;  // the session plays them in time order
  std::stable_sort(order.begin(), order.end(), [](const auto& x, const auto& y) { return x.time < y.time; });
  std::map<std::pair<std::size_t, std::size_t>, double> last_merge;  // (lower, higher index) -> session time
  std::vector<std::pair<std::string, std::size_t>> reasons;          // first seen first
  std::size_t next = 0, run = 0;
  for (const EncounterEvent& e : order) {
    const auto pair = std::minmax(e.a, e.b);
    const auto merged = last_merge.find(pair);
    const double last = merged == last_merge.end() ? -std::numeric_limits<double>::infinity() : merged->second;
    if (next < records.size() && records[next].time == e.time && records[next].a == names[e.a] &&
        records[next].b == names[e.b]) {
      if (records[next++].accepted) last_merge[pair] = e.time;
      ++run;
      continue;
    }
    const std::string why = skip_reason(e, names, first_clock, last, config);
    const auto seen = std::find_if(reasons.begin(), reasons.end(), [&](const auto& r) { return r.first == why; });
    if (seen == reasons.end()) {
      reasons.emplace_back(why, 1);
    } else {
      ++seen->second;
    }
  }
  std::string text = fmt::format("{} {}", events.size(), what);
  if (events.empty()) return text;
  text += fmt::format(": {} run", run);
  if (run == events.size()) return text;
  text += fmt::format(", {} skipped (", events.size() - run);
  for (std::size_t i = 0; i < reasons.size(); ++i) {
    text += i > 0 ? "; " : "";
    text += reasons.size() == 1 ? reasons[i].first : fmt::format("{}: {}", reasons[i].first, reasons[i].second);
  }
  return text + ")";
}

}  // namespace dsswarm
