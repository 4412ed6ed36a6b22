#include "agent/paced_feed.hpp"

#include <stdexcept>

namespace dsswarm::agent {

PacedFeed::PacedFeed(std::vector<LaserScan> scans, std::vector<double> clock, const PacedFeedConfig& config)
    : scans_(std::move(scans)), clock_(std::move(clock)), config_(config) {
  if (clock_.size() != scans_.size()) throw std::invalid_argument("PacedFeed: one clock time per scan");
  if (!(config_.rate > 0.0)) throw std::invalid_argument("PacedFeed: rate must be > 0");
  if (config_.queue_capacity == 0) throw std::invalid_argument("PacedFeed: queue capacity must be > 0");
  player_ = std::thread([this] { play(); });
}

PacedFeed::~PacedFeed() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  changed_.notify_all();
  player_.join();
}

std::chrono::steady_clock::time_point steady_start(const std::optional<std::chrono::system_clock::time_point>& start_at) {
  const auto now = std::chrono::steady_clock::now();
  if (!start_at) return now;
  return now + std::chrono::duration_cast<std::chrono::steady_clock::duration>(*start_at - std::chrono::system_clock::now());
}

void PacedFeed::play() {
  const auto start = steady_start(config_.start_at);
  for (std::size_t i = 0; i < scans_.size(); ++i) {
    const auto due = start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                 std::chrono::duration<double>(clock_[i] / config_.rate));
    std::unique_lock lock(mutex_);
    if (changed_.wait_until(lock, due, [&] { return stop_; })) return;
    if (queue_.size() >= config_.queue_capacity) {
      queue_.pop_front();
      ++dropped_;
    }
    queue_.push_back(std::move(scans_[i]));
    ++received_;
    changed_.notify_all();
  }
  std::lock_guard lock(mutex_);
  played_all_ = true;
  changed_.notify_all();
}

std::optional<LaserScan> PacedFeed::next(std::chrono::milliseconds timeout) {
  std::unique_lock lock(mutex_);
  changed_.wait_for(lock, timeout, [&] { return !queue_.empty() || played_all_ || woken_ || stop_; });
  woken_ = false;
  if (queue_.empty()) return std::nullopt;
  LaserScan s = std::move(queue_.front());
  queue_.pop_front();
  return s;
}

bool PacedFeed::exhausted() const {
  std::lock_guard lock(mutex_);
  return played_all_ && queue_.empty();
}

void PacedFeed::wake() {
  std::lock_guard lock(mutex_);
  woken_ = true;
  changed_.notify_all();
}

}  // namespace dsswarm::agent
