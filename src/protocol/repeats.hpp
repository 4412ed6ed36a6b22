#pragma once
// Encounters that would only repeat the last one. Two robots parked side by
// side are told they are near every few seconds; with neither having moved
// nor mapped anything since their last decided encounter, the same two
// scans from the same places on the same maps give the same placements —
// work and bytes for nothing, and no independent second estimate to
// confirm an unconfirmed transform with. Both robots judge it from the two
// offers, so both come to the same answer. An encounter turned down is run
// again a few times on the same offers all the same: a new random search
// may find what the last one missed.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "geometry/pose2.hpp"
#include "swarm/map_snapshot.hpp"

namespace dsswarm::protocol {

// What a robot put on the table: its pose and every layer it holds.
struct Offered {
  Pose2 pose;
  std::vector<LayerVersion> inventory;
};

class RepeatGuard {
 public:
  // Poses within `xy` m and `theta` rad count as the same place; a repeat
  // of one turned down is run again `retries` times.
  RepeatGuard(double xy, double theta, int retries = 0) : xy_(xy), theta_(theta), retries_(retries) {}

  // The pair's encounter `id` was decided on these offers (A's, B's);
  // `verified`: its placements passed every check (accepted or waiting for
  // confirmation), else it was turned down.
  void decided(const std::string& peer, std::uint64_t id, Offered a, Offered b, bool verified = true);
  // The encounter these offers repeat, if they match the pair's last decided
  // one and that one is not to be run again.
  std::optional<std::uint64_t> repeats(const std::string& peer, const Offered& a, const Offered& b) const;

 private:
  struct Last {
    std::uint64_t id = 0;
    Offered a, b;
    bool verified = true;
    int runs = 1;  // on these offers
  };
  bool same(const Offered& then, const Offered& now) const;

  double xy_, theta_;
  int retries_;
  std::map<std::string, Last> last_;
};

}  // namespace dsswarm::protocol
