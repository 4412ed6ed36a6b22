#include "apps/swarm_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <utility>

namespace dsswarm {
std::string describe_encounter_events(const std::string& what, std::size_t events, std::size_t run,
                                      const std::vector<std::string>& skipped) {
  std::string text = fmt::format("{} {}", events, what);
  if (events == 0) return text;
  text += fmt::format(": {} run", run);
  if (skipped.empty()) return text;
  std::vector<std::pair<std::string, std::size_t>> reasons;  // first seen first
  for (const std::string& why : skipped) {
    const auto seen = std::find_if(reasons.begin(), reasons.end(), [&](const auto& r) { return r.first == why; });
    if (seen == reasons.end()) {
      reasons.emplace_back(why, 1);
    } else {
      ++seen->second;
    }
  }
  text += fmt::format(", {} skipped (", skipped.size());
  for (std::size_t i = 0; i < reasons.size(); ++i) {
    text += i > 0 ? "; " : "";
    text += reasons.size() == 1 ? reasons[i].first : fmt::format("{}: {}", reasons[i].first, reasons[i].second);
  }
  return text + ")";
}

std::string describe_robot_processes(const SwarmRunResult& run, const std::vector<nlohmann::json>& agent_stats) {
  std::string text;
  std::vector<double> medians, maxima;
  double late = 0.0;
  for (std::size_t i = 0; i < run.agents.size() && i < agent_stats.size(); ++i) {
    const nlohmann::json& s = agent_stats[i];
    auto number = [&](const char* key) { return s.contains(key) && s[key].is_number() ? s[key].get<double>() : 0.0; };
    std::string latency = "no merge";
    if (s.contains("merge_ready_ms") && s["merge_ready_ms"].is_object()) {
      const double median = s["merge_ready_ms"]["median"].get<double>(), max = s["merge_ready_ms"]["max"].get<double>();
      latency = fmt::format("merged map ready median {:.0f} ms, max {:.0f} ms; {:.0f} late", median, max,
                            number("merges_late"));
      medians.push_back(median);
      maxima.push_back(max);
      late += number("merges_late");
    }
    text += fmt::format("  {}: {:.0f} scans processed, {:.0f} skipped; CPU {:.1f} s; largest scan gap during an "
                        "encounter {:.0f} ms; {}\n",
                        run.agents[i].name, number("scans_processed"), number("scans_skipped"), number("cpu_seconds"),
                        number("largest_scan_gap_during_encounter_ms"), latency);
  }
  std::sort(medians.begin(), medians.end());
  if (!maxima.empty())
    text += fmt::format("  merge latency (proximity event to merged map composed): median of robots {:.0f} ms, max "
                        "{:.0f} ms; {:.0f} merge(s) not ready by their scan (swarm.merge_delay after the encounter's)\n",
                        medians[medians.size() / 2], *std::max_element(maxima.begin(), maxima.end()), late);
  return text;
}

std::string describe_simulated_outcome(const nlohmann::json& stats) {
  std::string text;
  for (const auto& agent : stats["agents"])
    text += fmt::format("  {}: ATE RMSE {:.3f} m, map covers {:.0f}% of what the swarm explored, knows {} other robot(s)\n",
                        agent["name"].get<std::string>(), agent["ate_rmse"].get<double>(),
                        100.0 * agent["coverage"].get<double>(), agent["knows"].size());
  if (stats["encounters_accepted"].get<std::size_t>() == 0) return text + "nothing was merged: no encounter was accepted\n";
  return text + fmt::format(
                    "worst accepted transform error {:.3f} m / {:.2f}° against the map frames as they stood (causal), "
                    "{:.3f} m / {:.2f}° against the robots' true relative pose; {} wrong merges (> 0.3 m or 3° against "
                    "both the robots' true relative pose and the aligned frames)\n",
                    stats["worst_accepted_causal_error"][0].get<double>(),
                    stats["worst_accepted_causal_error"][1].get<double>(), stats["worst_accepted_error"][0].get<double>(),
                    stats["worst_accepted_error"][1].get<double>(), stats["wrong_merges"].get<std::size_t>());
}

}  // namespace dsswarm
