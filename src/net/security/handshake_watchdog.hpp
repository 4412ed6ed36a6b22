#pragma once
// Works around a Cyclone DDS 0.10 bug (cyclonedds #1895): under packet loss
// the security handshake between two participants can time out and is never
// retried, so two authorised robots stay deaf to each other for good, most
// often after one of them restarts. Discovery still shows the other
// participant; none of its endpoints ever match ours. The remedy that works
// (docs/security.md) is to delete our participant and create it again: a new
// GUID means fresh handshakes with every peer.
//
// The watchdog only decides. The caller polls discovery (which remote
// participants are alive, which have an endpoint matched with ours; see
// DiscoveryProbe), passes that to update(), and when it says so recreates
// its participant with all its endpoints and calls recreated(). Recreation
// is rate-limited with exponential backoff: a participant that can never
// match (an intruder from another CA, a revoked robot) costs at most one
// brief re-handshake per backoff period, not a storm.
#include <chrono>
#include <cstddef>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace dsswarm::security {

struct HandshakeWatchdogConfig {
  // A remote participant alive this long without a matched endpoint is stuck.
  // A handshake takes ~0.2 s on loopback and a few seconds under heavy loss.
  // Keep it above the participant lease duration (Cyclone's default 10 s): a
  // peer killed without a goodbye stays in discovery until its lease expires,
  // and after a recreation it can never match the new participant.
  double stuck_after_s = 15.0;
  // Minimum time between two recreations; doubles after each recreation that
  // is followed by another stuck participant, back to this once all are matched.
  double first_backoff_s = 30.0;
  double max_backoff_s = 600.0;
};

class HandshakeWatchdog {
 public:
  using Clock = std::chrono::steady_clock;

  explicit HandshakeWatchdog(HandshakeWatchdogConfig config = {});

  // One poll of discovery: remote participants (any stable key, e.g. the
  // GUID as text) alive now, and those with an endpoint matched to ours.
  // True when the caller should recreate its participant now.
  bool update(const std::set<std::string>& alive, const std::set<std::string>& matched, Clock::time_point now);

  // The caller has recreated its participant: every remote participant has
  // to handshake with the new one, so their clocks restart.
  void recreated(Clock::time_point now);

  // Remote participants currently counted as stuck (for logs).
  std::vector<std::string> stuck(Clock::time_point now) const;
  std::size_t recreations() const { return recreations_; }

 private:
  double seconds(Clock::duration d) const { return std::chrono::duration<double>(d).count(); }

  HandshakeWatchdogConfig config_;
  std::map<std::string, Clock::time_point> unmatched_since_;  // alive, never matched
  std::set<std::string> matched_;
  Clock::time_point not_before_{};  // no recreation before this
  double backoff_s_;
  std::size_t recreations_ = 0;
};

}  // namespace dsswarm::security
