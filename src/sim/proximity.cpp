#include "sim/proximity.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/errors.hpp"

namespace dsswarm {
namespace {

// Line of sight: the straight line keeps this far from every wall (it is
// blocked when it only grazes a corner).
constexpr double kLineOfSightClearance = 0.05;
// Timestamps are k / rate; an interval of 15 s must not miss by a rounding error.
constexpr double kTimeTolerance = 1e-9;

std::string robot_name(const SimulatedSwarm& swarm, std::size_t r) {
  return r < swarm.names.size() ? swarm.names[r] : "robot index " + std::to_string(r);
}

// All robots must share one clock: same number of poses and timestamps.
void check_one_clock(const SimulatedSwarm& swarm) {
  const auto& first = swarm.runs.front().ground_truth;
  for (std::size_t r = 0; r < swarm.runs.size(); ++r) {
    const auto& truth = swarm.runs[r].ground_truth;
    if (truth.size() != first.size())
      throw InputError("proximity: " + robot_name(swarm, r) + " has " + std::to_string(truth.size()) +
                       " ground-truth poses, " + robot_name(swarm, 0) + " has " + std::to_string(first.size()) +
                       "; the sensor needs all robots on one clock");
    for (std::size_t k = 0; k < truth.size(); ++k) {
      const auto& [time, pose] = truth[k];
      if (!std::isfinite(time) || !std::isfinite(pose.x) || !std::isfinite(pose.y))
        throw InputError("proximity: " + robot_name(swarm, r) + " ground-truth pose " + std::to_string(k) +
                         " is not finite");
      if (std::abs(time - first[k].first) > kTimeTolerance)
        throw InputError("proximity: " + robot_name(swarm, r) + " ground-truth pose " + std::to_string(k) +
                         " has timestamp " + std::to_string(time) + ", " + robot_name(swarm, 0) + " has " +
                         std::to_string(first[k].first) + "; the sensor needs all robots on one clock");
    }
  }
}

}  // namespace

void validate(const ProximityConfig& c) {
  require_config("proximity config", std::isfinite(c.range) && c.range > 0, "range must be a positive number of metres");
  require_config("proximity config", !std::isnan(c.repeat_interval) && c.repeat_interval > 0,
          "repeat_interval must be a positive number of seconds (or infinity)");
}

std::vector<ProximityEvent> proximity_events(const World& world, const SimulatedSwarm& swarm,
                                             const ProximityConfig& config) {
  validate(config);
  std::vector<ProximityEvent> events;
  if (swarm.runs.size() < 2) return events;
  check_one_clock(swarm);

  const std::size_t robots = swarm.runs.size();
  const std::size_t steps = swarm.runs.front().ground_truth.size();
  struct PairState {
    bool near = false;
    double last_event = 0.0;
  };
  std::vector<PairState> pairs(robots * robots);
  // Steps in time order and pairs in (a, b) order: the events come out sorted.
  for (std::size_t k = 0; k < steps; ++k) {
    const double time = swarm.runs.front().ground_truth[k].first;
    for (std::size_t a = 0; a < robots; ++a) {
      const Eigen::Vector2d pa = swarm.runs[a].ground_truth[k].second.translation();
      for (std::size_t b = a + 1; b < robots; ++b) {
        const Eigen::Vector2d pb = swarm.runs[b].ground_truth[k].second.translation();
        PairState& state = pairs[a * robots + b];
        const bool near = (pa - pb).norm() <= config.range &&
                          (!config.line_of_sight || world.is_segment_free(pa, pb, kLineOfSightClearance));
        if (near && (!state.near || time - state.last_event >= config.repeat_interval - kTimeTolerance)) {
          events.push_back({time, static_cast<int>(a), static_cast<int>(b)});
          state.last_event = time;
        }
        state.near = near;
      }
    }
  }
  // Already in order for one clock; sorting keeps the promise for hand-made
  // timestamps that run backwards too.
  std::stable_sort(events.begin(), events.end(), [](const ProximityEvent& x, const ProximityEvent& y) {
    if (x.time != y.time) return x.time < y.time;
    return x.a != y.a ? x.a < y.a : x.b < y.b;
  });
  return events;
}

}  // namespace dsswarm
