#pragma once
// One warning per interval about a stream of rejected network samples: a peer
// sending garbage at 1 kHz must not flood stderr, and nothing goes unsaid.
#include <spdlog/spdlog.h>

#include <chrono>
#include <cstdint>
#include <string>
#include <utility>

namespace dsswarm::net {

class WarningThrottle {
 public:
  using Clock = std::chrono::steady_clock;

  WarningThrottle(std::string what, std::chrono::milliseconds interval) : what_(std::move(what)), interval_(interval) {}

  // Counts one rejection; warns (with the count since the last warning and
  // this reason) at most once per interval.
  void note(const std::string& reason, Clock::time_point now = Clock::now()) {
    ++unreported_;
    if (reported_once_ && now - last_warning_ < interval_) return;
    spdlog::warn("{}: {} rejected since the last report; latest: {}", what_, unreported_, reason);
    unreported_ = 0;
    last_warning_ = now;
    reported_once_ = true;
  }

 private:
  std::string what_;
  std::chrono::milliseconds interval_;
  Clock::time_point last_warning_{};
  bool reported_once_ = false;
  std::uint64_t unreported_ = 0;
};

}  // namespace dsswarm::net
