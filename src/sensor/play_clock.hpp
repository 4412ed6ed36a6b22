#pragma once
// The play clock of a recorded run: when each scan is played, in seconds
// after the first one — `dsswarm replay`, `agent --log` and the session
// clock of scenario files all play by it. It is the time since the first
// stamp in the direction of play, held at its running maximum where stamps
// run the other way: file order is the true order (intel's stamps run
// backwards now and then), so such a scan goes out at once instead of
// stalling the run.
#include <span>
#include <vector>

#include "sensor/laser_scan.hpp"

namespace dsswarm {

enum class PlayDirection { forward, backward };

// `stamps` in play order (played backward: the file's last scan first).
std::vector<double> play_clock(std::span<const double> stamps, PlayDirection direction = PlayDirection::forward);
std::vector<double> play_clock(const std::vector<LaserScan>& scans, PlayDirection direction = PlayDirection::forward);

}  // namespace dsswarm
