#pragma once
// What the log readers' tests ask of a read log's warnings (CARMEN, ROS1 and
// ROS 2 bags).
#include <algorithm>
#include <string>
#include <vector>

#include "sensor/laser_scan.hpp"

namespace dsswarm::test {

// Whether any warning contains `text`.
inline bool has_warning(const SensorLog& log, const std::string& text) {
  return std::any_of(log.warnings.begin(), log.warnings.end(),
                     [&](const std::string& w) { return w.find(text) != std::string::npos; });
}

// The lines, each ended by a newline: every warning in a failure message.
inline std::string joined(const std::vector<std::string>& lines) {
  std::string out;
  for (const auto& l : lines) out += l + "\n";
  return out;
}

}  // namespace dsswarm::test
