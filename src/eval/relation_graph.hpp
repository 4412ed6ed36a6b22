#pragma once
// Encounter truth for `eval swarm`: the motion between two scan timestamps, chained
// from benchmark relations.
#include <cstddef>
#include <optional>
#include <vector>

#include "eval/relations.hpp"
#include "geometry/pose2.hpp"

namespace dsswarm {

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

}  // namespace dsswarm
