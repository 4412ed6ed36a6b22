#include "net/security/handshake_watchdog.hpp"

#include <algorithm>

#include "common/errors.hpp"

namespace dsswarm::security {

HandshakeWatchdog::HandshakeWatchdog(HandshakeWatchdogConfig config)
    : config_(config), backoff_s_(config.first_backoff_s) {
  if (!(config.stuck_after_s > 0) || !(config.first_backoff_s > 0) || !(config.max_backoff_s >= config.first_backoff_s)) {
    throw ConfigError("handshake watchdog: stuck_after_s and first_backoff_s must be > 0, max_backoff_s >= first_backoff_s");
  }
}

bool HandshakeWatchdog::update(const std::set<std::string>& alive, const std::set<std::string>& matched,
                               Clock::time_point now) {
  for (auto it = unmatched_since_.begin(); it != unmatched_since_.end();) {
    it = (!alive.count(it->first) || matched.count(it->first)) ? unmatched_since_.erase(it) : std::next(it);
  }
  std::erase_if(matched_, [&](const std::string& p) { return !alive.count(p); });
  for (const auto& p : alive) {
    if (matched.count(p)) {
      matched_.insert(p);
    } else if (!matched_.count(p)) {
      unmatched_since_.emplace(p, now);  // keeps the first time seen
    }
  }
  if (unmatched_since_.empty()) backoff_s_ = config_.first_backoff_s;  // healthy again
  return now >= not_before_ && !stuck(now).empty();
}

void HandshakeWatchdog::recreated(Clock::time_point now) {
  ++recreations_;
  for (auto& entry : unmatched_since_) entry.second = now;
  matched_.clear();  // they must match our new participant
  not_before_ = now + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(backoff_s_));
  backoff_s_ = std::min(2 * backoff_s_, config_.max_backoff_s);
}

std::vector<std::string> HandshakeWatchdog::stuck(Clock::time_point now) const {
  std::vector<std::string> out;
  for (const auto& [p, since] : unmatched_since_)
    if (seconds(now - since) >= config_.stuck_after_s) out.push_back(p);
  return out;
}

}  // namespace dsswarm::security
