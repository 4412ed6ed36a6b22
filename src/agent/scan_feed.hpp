#pragma once
// Where a robot process gets its scans: live ROS 2 topics (net/), or a log
// or simulated run played in real time (paced_feed.hpp). A feed never queues
// without bound: when the robot falls behind, the oldest scans are dropped
// and counted.
#include <chrono>
#include <cstdint>
#include <optional>

#include "sensor/laser_scan.hpp"

namespace dsswarm::agent {

class ScanFeed {
 public:
  virtual ~ScanFeed() = default;
  // The oldest scan waiting, or nullopt after `timeout` (or wake()).
  virtual std::optional<LaserScan> next(std::chrono::milliseconds timeout) = 0;
  // A recorded feed that has handed out everything (a live feed: never).
  virtual bool exhausted() const = 0;
  virtual void wake() = 0;
  virtual std::uint64_t received() const = 0;  // scans that arrived
  virtual std::uint64_t dropped() const = 0;   // of which skipped: the robot was behind
};

}  // namespace dsswarm::agent
