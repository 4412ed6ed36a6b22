#pragma once
// A recorded run played in real time × rate, as a robot's lidar would
// deliver it: scan i becomes available at start + clock[i] / rate (wall
// time), whatever the robot is doing, into a small queue that drops its
// oldest scan when the robot falls behind.
#include <atomic>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "agent/scan_feed.hpp"
#include "sensor/play_clock.hpp"  // the clocks PacedFeed plays by

namespace dsswarm::agent {

struct PacedFeedConfig {
  double rate = 1.0;             // × real time
  std::size_t queue_capacity = 8;  // scans waiting for the robot; the oldest is dropped beyond
  // When clock 0 is (robots of one launch start together); default: now.
  std::optional<std::chrono::system_clock::time_point> start_at;
};

// The steady-clock moment of `start_at` (or now).
std::chrono::steady_clock::time_point steady_start(const std::optional<std::chrono::system_clock::time_point>& start_at);

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

}  // namespace dsswarm::agent
