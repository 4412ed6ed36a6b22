#pragma once
// One encounter in progress, shared by the engine's parts: the offers,
// placements and decision (encounter_engine.cpp), the snapshot transfer and
// merge (encounter_transfer.cpp), and how encounters end and what follows a
// merge (encounter_endings.cpp). Private to the engine.
#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include "protocol/encounter_engine.hpp"
#include "protocol/transfer.hpp"

namespace dsswarm::protocol {

inline double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

struct EncounterEngine::Exchange {
  std::string peer;
  std::uint64_t id = 0;
  bool self_is_a = true;
  CapturedView mine;
  std::optional<Offer> offer;  // the peer's
  std::optional<PeerPlacement> my_placement;
  std::optional<Placement> their_placement;
  std::vector<LayerVersion> my_inventory;  // as offered
  std::optional<Pose2> my_known;  // confirmation candidates as sent
  std::vector<Pose2> my_pending;
  bool decided = false;
  bool accepted = false;
  double progress = 0.0;  // the caller's clock when it opened, then when the peer's offer came (time-outs count from here)
  TransferAssembler incoming;
  EncounterOutcome outcome;

  // Each robot's pose at the scan it offered (requires the peer's offer).
  const Pose2& a_pose() const { return self_is_a ? mine.view.pose : offer->pose; }
  const Pose2& b_pose() const { return self_is_a ? offer->pose : mine.view.pose; }
};

}  // namespace dsswarm::protocol
