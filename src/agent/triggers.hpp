#pragma once
// Proximity events that name the scan to act after (replayed logs and
// simulations, so that a robot process repeats the in-process swarm
// exactly): an armed event fires once the robot has processed the scan with
// that stamp — at once if it already has — or, if that scan never comes
// (skipped while the robot was behind), after a patience time.
#include <chrono>
#include <cstdint>
#include <deque>
#include <string>
#include <vector>

namespace dsswarm::agent {

struct Trigger {
  std::string peer;
  std::uint64_t encounter = 0;
  double stamp = 0.0;
  std::chrono::steady_clock::time_point armed_at;
  bool late = false;  // fired by patience or after its scan had passed
};

class TriggerBook {
 public:
  explicit TriggerBook(std::chrono::milliseconds patience, std::size_t remembered_stamps = 4096)
      : patience_(patience), remembered_(remembered_stamps) {}

  // Returns the trigger at once (late) when the scan was already processed.
  std::vector<Trigger> arm(Trigger t);
  // After each processed scan: the triggers due.
  std::vector<Trigger> on_scan(double stamp);
  // Triggers that have waited longer than the patience.
  std::vector<Trigger> overdue(std::chrono::steady_clock::time_point now);
  bool armed(const std::string& peer, std::uint64_t encounter) const;
  std::size_t size() const { return armed_.size(); }

 private:
  std::chrono::milliseconds patience_;
  std::size_t remembered_;
  std::vector<Trigger> armed_;
  std::deque<double> recent_;  // stamps processed lately
};

}  // namespace dsswarm::agent
