#pragma once
// /map of a robot process, about once a second (RobotOutputs::map_due).
// With loop closure on, the map is composed on a thread of its own from the
// parts taken under the agent's lock (swarm/live_map.hpp) and handed back to
// the scan loop, which publishes it: the scan path pays for a copy of the
// growing submap, not for composing every submap, and the map shows the
// graph as it is now. Without loop closure the working map is the map, kept
// up to date scan by scan: it is rasterized where it stands.
#include <memory>
#include <mutex>
#include <optional>
#include <utility>

#include "agent/robot_outputs.hpp"
#include "agent/shared_agent.hpp"
#include "grid/grid_raster.hpp"
#include "runtime/worker_thread.hpp"
#include "swarm/live_map.hpp"

namespace dsswarm::agent {

class LiveMapOutput {
 public:
  LiveMapOutput(const SharedAgent& agent, RobotOutputs& outputs);
  // The scan loop, after each scan (`stamp` its time): publishes a map
  // composed since, and starts the next one when one is due.
  void after_scan(double stamp, SteadyClock::time_point now);
  // Maps composed off the scan path so far.
  std::size_t composed() const;

 private:
  void publish_ready();

  const SharedAgent& agent_;
  RobotOutputs& outputs_;
  LiveMap live_;  // the worker's
  mutable std::mutex mutex_;
  std::optional<std::pair<GridRaster, double>> ready_;
  bool in_flight_ = false;
  std::size_t composed_ = 0;
  WorkerThread worker_;  // last: its jobs use everything above
};

}  // namespace dsswarm::agent
