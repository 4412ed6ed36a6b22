#include "sensor/play_clock.hpp"

#include <algorithm>

namespace dsswarm {

std::vector<double> play_clock(std::span<const double> stamps, PlayDirection direction) {
  std::vector<double> clock;
  clock.reserve(stamps.size());
  const double sign = direction == PlayDirection::backward ? -1.0 : 1.0;
  double elapsed = 0.0;
  for (const double t : stamps) {
    elapsed = std::max(elapsed, sign * (t - stamps.front()));
    clock.push_back(elapsed);
  }
  return clock;
}

std::vector<double> play_clock(const std::vector<LaserScan>& scans, PlayDirection direction) {
  std::vector<double> stamps;
  stamps.reserve(scans.size());
  for (const LaserScan& s : scans) stamps.push_back(s.timestamp);
  return play_clock(stamps, direction);
}

}  // namespace dsswarm
