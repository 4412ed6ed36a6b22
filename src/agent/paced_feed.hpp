#pragma once
// A recorded run played in real time × rate, as a robot's lidar would
// deliver it: scan i becomes available at start + clock[i] / rate (wall
// time), whatever the robot is doing, into a small queue that drops its
// oldest scan when the robot falls behind.
#include <atomic>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <thread>
#include <vector>

#include "agent/scan_feed.hpp"

namespace dsswarm::agent {

struct PacedFeedConfig {
  double rate = 1.0;             // × real time
  std::size_t queue_capacity = 8;  // scans waiting for the robot; the oldest is dropped beyond
};

class PacedFeed : public ScanFeed {
 public:
  // `clock[i]`: seconds after the start at which scan i is played (non-decreasing).
  PacedFeed(std::vector<LaserScan> scans, std::vector<double> clock, const PacedFeedConfig& config);
  ~PacedFeed() override;

  std::optional<LaserScan> next(std::chrono::milliseconds timeout) override;
  bool exhausted() const override;
  void wake() override;
  std::uint64_t received() const override { return received_; }
  std::uint64_t dropped() const override { return dropped_; }

 private:
  void play();

  std::vector<LaserScan> scans_;
  std::vector<double> clock_;
  PacedFeedConfig config_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<LaserScan> queue_;
  bool played_all_ = false;
  bool stop_ = false;
  bool woken_ = false;
  std::atomic<std::uint64_t> received_{0}, dropped_{0};
  std::thread player_;  // last: starts once everything above exists
};

// The play clock of a log as `dsswarm replay` and scenarios use it: scan i at
// t_i − t_0, held at the running maximum where timestamps run backwards.
std::vector<double> play_clock(const std::vector<LaserScan>& scans);

}  // namespace dsswarm::agent
