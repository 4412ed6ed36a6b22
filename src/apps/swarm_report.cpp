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

}  // namespace dsswarm
