#pragma once
// A simulated proximity sensor for a swarm (think short-range radio or a
// fiducial seen by a camera): it tells two robots when they are near each
// other, which is when they exchange maps. It fires when a pair comes within
// range with a clear line between them, and again at intervals while they
// stay near, so a rejected map merge can be retried.
#include <vector>

#include "sim/swarm_sim.hpp"
#include "sim/world.hpp"

namespace dsswarm {

struct ProximityConfig {
  double range = 3.0;             // m between the robots' true base positions
  bool line_of_sight = true;      // require a wall-free straight line between them
  double repeat_interval = 15.0;  // s between events while a pair stays near (+infinity: only on meeting)
};

// Throws ConfigError naming the field.
void validate(const ProximityConfig& config);

struct ProximityEvent {
  double time;  // the scan timestamp
  int a;        // robot indices into the swarm, a < b
  int b;
  bool operator==(const ProximityEvent&) const = default;
};

// Events from the robots' ground truth, sorted by time, then (a, b). A pair
// fires on the first scan it is near (within range and, if required, in
// line of sight), then every repeat_interval seconds while it stays near;
// once it is not near any more, coming back fires again at once.
// Throws InputError when the robots' ground truths are not on one clock
// (different lengths or timestamps) or hold non-finite values.
std::vector<ProximityEvent> proximity_events(const World& world, const SimulatedSwarm& swarm,
                                             const ProximityConfig& config);

}  // namespace dsswarm
