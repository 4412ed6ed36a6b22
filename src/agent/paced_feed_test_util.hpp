#pragma once
// For the agent's tests: a paced feed's configuration in one call.
#include <cstddef>

#include "agent/paced_feed.hpp"

namespace dsswarm::agent {

inline PacedFeedConfig paced(double rate, std::size_t queue) {
  PacedFeedConfig c;
  c.rate = rate;
  c.queue_capacity = queue;
  return c;
}

}  // namespace dsswarm::agent
