#pragma once
// A simulated swarm run scored against its ground truth: each robot's ATE and
// how much of what the swarm explored its final map covers, and each
// encounter's transform error under four references for "true" (a map frame
// has no single true place once its map has drifted):
//   frame_error:   the true poses where the two robots started;
//   aligned_error: each map frame as its whole trajectory best fits the truth
//                  (the ATE alignment): drift averaged out, in hindsight;
//   causal_error:  the same with each trajectory only up to the encounter:
//                  the maps as they were when merged (the fairest);
//   error:         the robots' true relative pose where they met, from their
//                  own pose estimates there.
// Each as [metres, degrees], taken at robot B's position.
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "eval/swarm_run.hpp"

namespace dsswarm {

struct AgentTruthScore {
  double ate_rmse = 0.0;
  double coverage = 0.0;  // share of the swarm's explored cells its working map knows
};

// Throws ConfigError when truth and run disagree on the agents.
std::vector<AgentTruthScore> score_agents(const SwarmRunResult& run, const SwarmTruth& truth);

struct ErrorPair {
  double metres = 0.0, degrees = 0.0;
};

struct EncounterTruthScore {
  Pose2 true_transform;  // B's map frame in A's, from where they started
  ErrorPair frame_error, aligned_error, error;
  std::optional<ErrorPair> causal_error;
  ErrorPair placement_a, placement_b;  // each robot's placement of the other, against the truth
  bool wrong = false;  // accepted and off by more than 0.3 m or 3° under both `error` and `aligned_error`
};

// One scorer per run: it holds each agent's whole-trajectory alignment.
class EncounterScorer {
 public:
  EncounterScorer(const SwarmRunResult& run, const SwarmTruth& truth);
  EncounterTruthScore score(const EncounterRecord& r) const;

 private:
  std::size_t index_of(const std::string& name) const;
  const SwarmRunResult& run_;
  const SwarmTruth& truth_;
  std::vector<Pose2> alignments_;
};

// The estimate an encounter record carries: the accepted transform, else the
// candidate it turned down (A's placement of B).
Pose2 record_transform(const EncounterRecord& r);

nlohmann::json to_json(const EncounterTruthScore& s);

}  // namespace dsswarm
