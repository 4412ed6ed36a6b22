#include "agent/live_map_output.hpp"

namespace dsswarm::agent {

LiveMapOutput::LiveMapOutput(const SharedAgent& agent, RobotOutputs& outputs) : agent_(agent), outputs_(outputs) {}

std::size_t LiveMapOutput::composed() const {
  std::lock_guard lock(mutex_);
  return composed_;
}

void LiveMapOutput::publish_ready() {
  std::optional<std::pair<GridRaster, double>> ready;
  {
    std::lock_guard lock(mutex_);
    ready.swap(ready_);
  }
  if (ready) outputs_.map(std::move(ready->first), ready->second);
}

void LiveMapOutput::after_scan(double stamp, SteadyClock::time_point now) {
  publish_ready();
  {
    std::lock_guard lock(mutex_);
    if (in_flight_ || ready_) return;
  }
  if (!outputs_.map_due(now)) return;
  auto parts = agent_.with_agent([](const SwarmAgent& a) { return a.live_map_parts(); });
  if (!parts) {
    outputs_.map(agent_.with_agent([](const SwarmAgent& a) { return a.slam().map().finest().to_raster(); }), stamp);
    return;
  }
  {
    std::lock_guard lock(mutex_);
    in_flight_ = true;
  }
  worker_.submit([this, parts = std::make_shared<const LiveMapParts>(std::move(*parts)), stamp] {
    GridRaster raster = live_.compose(*parts).finest().to_raster();
    std::lock_guard lock(mutex_);
    ready_.emplace(std::move(raster), stamp);
    in_flight_ = false;
    ++composed_;
  });
}

}  // namespace dsswarm::agent
