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
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "eval/relations.hpp"
#include "geometry/pose2.hpp"
#include "io/trajectory/tum.hpp"

namespace dsswarm {

// One entry of encounters.json.
struct SwarmEncounterEntry {
  double time = 0.0;           // session clock, s
  std::string a, b;            // agent names
  double a_log_time = 0.0;     // timestamps of the scans exchanged
  double b_log_time = 0.0;
  Pose2 a_pose;                // a's pose in a's frame at the encounter
  Pose2 b_pose;                // b's pose in b's frame
  std::optional<Pose2> transform;  // b's frame in a's frame (a candidate only, when rejected)
  bool accepted = false;
  std::string reason;
  std::optional<double> match_ms, merge_ms, bytes;
};

// Reads {"encounters": [...]}. Required per entry: time, agents, log_times,
// poses, accepted; transform when accepted (may be null otherwise); reason,
// match_ms, merge_ms, bytes optional; other keys are ignored (simulation adds
// its own). Throws InputError naming the file, the entry and the field.
std::vector<SwarmEncounterEntry> read_swarm_encounters(const std::filesystem::path& path);

struct SwarmAgentOutput {
  std::string name;
  Trajectory own;                  // agents/<name>/trajectory.tum
  std::optional<Trajectory> joint; // joint/<name>.tum, when its transform was known
};

struct SwarmOutput {
  std::vector<SwarmAgentOutput> agents;  // sorted by name
  std::vector<SwarmEncounterEntry> encounters;
};

// Reads a swarm output folder. encounters.json may be absent (no encounters);
// agents/ must hold at least one agent with a trajectory.tum.
SwarmOutput read_swarm_output(const std::filesystem::path& dir);

// The truth between two scan timestamps, from relations alone:
//   * the same timestamp (within max_time_diff): no motion;
//   * else both timestamps must be relation endpoints (within max_time_diff),
//     and the truth is the shortest chain of relations joining them (fewest
//     relations, breadth-first, relations in file order), composed end to end
//     (a relation walked from t2 to t1 counts inverted), if it has at most
//     `max_hops` relations. One hop is the relation with exactly those
//     timestamps. Each chained relation adds its own small error, so the hop
//     count is reported with the result;
//   * otherwise there is no truth ("no relation").
class RelationGraph {
 public:
  RelationGraph(const std::vector<Relation>& relations, double max_time_diff);

  struct Truth {
    Pose2 motion;     // from the pose at ta to the pose at tb, in ta's frame
    std::size_t hops = 0;  // relations chained (0: the same scan)
  };
  std::optional<Truth> motion(double ta, double tb, std::size_t max_hops) const;

  // Relation timestamps within `window` s of t, nearest first.
  std::vector<double> endpoints_near(double t, double window) const;

 private:
  std::optional<std::size_t> node_at(double t) const;

  struct Edge {
    std::size_t to;
    std::size_t relation;
    bool forward;  // walked from the relation's t1 to its t2
  };
  std::vector<Relation> relations_;
  double max_time_diff_;
  std::vector<double> node_times_;  // sorted; endpoints within max_time_diff share a node
  std::vector<std::vector<Edge>> edges_;
};

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
