#pragma once
// Scores what `dsswarm swarm` wrote (DIR/agents/<name>/trajectory.tum,
// DIR/joint/<name>.tum, DIR/encounters.json) against benchmark relations
// (Kümmerle et al. 2009) of the log the agents played:
//
// * per agent: the relation metric on its own trajectory, over the relations
//   whose two timestamps the agent covers;
// * cross-agent: relations whose t1 only agent X covers and whose t2 only
//   agent Y ≠ X covers, scored on the joint trajectories (one common frame);
//   this is what merging buys: the two robots' poses are consistent with each other;
//   and again with each pair's frame fitted to its cross relations in
//   hindsight (cross_frame.hpp), which needs no merge;
// * per encounter: the estimated relative pose of b w.r.t. a,
//   pose_a⁻¹ ⊕ transform ⊕ pose_b, against the true motion between the two
//   scans exchanged (log times ta, tb), see RelationGraph for the truth rule.
//   Most scans are no relation's endpoint. Then the transform (which relates
//   two fixed map frames, whenever it was measured) is checked at the
//   relation timestamps nearest to ta and tb (within `bridge` seconds) that
//   each agent covers, with the agents' own poses there:
//   pose_a(ta')⁻¹ ⊕ transform ⊕ pose_b(tb') against the truth from ta' to tb'.
//   That adds each agent's own drift over at most `bridge` seconds to the error.
//
// "Covers t" is the rule of `eval relations`: the agent has a pose whose
// timestamp is within max_time_diff of t.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "eval/relation_graph.hpp"
#include "eval/relations.hpp"
#include "eval/swarm_output.hpp"
#include "geometry/pose2.hpp"

namespace dsswarm {

struct SwarmEvalOptions {
  double max_time_diff = 0.001;  // s, as `eval relations`
  std::size_t max_hops = 4;      // longest relation chain accepted as encounter truth
  double bridge = 2.0;           // s: how far from the exchanged scans an encounter may be checked (0: never)
};

struct AgentRelationScore {
  std::string name;
  std::size_t poses = 0;
  bool joint = false;                     // has a pose in the common frame
  std::size_t relations_covered = 0;      // both timestamps covered by this agent
  std::optional<RelationMetrics> metrics; // on its own trajectory (none if nothing covered)
};

struct CrossAgentScore {
  std::string x, y;  // the agents covering t1 and t2 (a pair is listed once, in agent order)
  std::size_t relations = 0;          // cross relations between the two
  std::size_t without_joint = 0;      // of those, not scored: an agent has no joint pose
  std::optional<RelationMetrics> metrics;
  // The frame fitted to these relations in hindsight (cross_frame.hpp) from
  // the agents' own trajectories, and the relations scored there: the part
  // of the error no frame estimate could remove.
  std::optional<Pose2> hindsight_frame;
  std::optional<RelationMetrics> hindsight;
};

struct EncounterScore {
  std::size_t index = 0;  // in encounters.json
  SwarmEncounterEntry entry;
  double a_time = 0.0, b_time = 0.0;      // where it is checked: the log times exchanged, or the bridged ones
  std::optional<Pose2> estimated_motion;  // pose_a⁻¹ ⊕ transform ⊕ pose_b at those times
  std::optional<RelationGraph::Truth> truth;
  bool bridged() const { return a_time != entry.a_log_time || b_time != entry.b_log_time; }
  double trans_error = 0.0;    // m (when estimate and truth are both known)
  double rot_error_deg = 0.0;  // deg
  bool scored() const { return estimated_motion && truth; }
};

struct SwarmEvaluation {
  std::vector<AgentRelationScore> agents;
  std::size_t cross_relations = 0;        // relations linking two agents, over all pairs
  std::size_t cross_without_joint = 0;
  std::optional<RelationMetrics> cross;   // all cross relations scored on the joint trajectories
  std::vector<CrossAgentScore> pairs;     // pairs with at least one cross relation
  std::vector<EncounterScore> encounters;
  std::size_t relations_total = 0;
  SwarmEvalOptions options;
};

// Throws ConfigError for a bad max_time_diff, InputError for non-finite poses.
SwarmEvaluation evaluate_swarm(const SwarmOutput& output, const std::vector<Relation>& relations,
                               const SwarmEvalOptions& options = {});

// The same figures as a readable table, and as one JSON object.
std::string format_swarm_evaluation(const SwarmEvaluation& evaluation);
nlohmann::json to_json(const SwarmEvaluation& evaluation);

}  // namespace dsswarm
