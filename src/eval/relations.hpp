#pragma once
// The relation-based SLAM metric of Kümmerle et al., "On measuring the
// accuracy of SLAM algorithms" (Autonomous Robots 2009): a trajectory is
// scored by how well it reproduces true relative motions between pairs of
// timestamps, which needs no global ground truth and is independent of the
// map's reference frame.
#include <cstddef>
#include <filesystem>
#include <istream>
#include <string>
#include <vector>

#include "geometry/pose2.hpp"
#include "io/trajectory/tum.hpp"

namespace dsswarm {

struct Relation {
  double t1 = 0.0;
  double t2 = 0.0;
  Pose2 motion;  // true motion from the pose at t1 to the pose at t2, in the frame of the pose at t1
};

// Reads a relation file: one relation per line, "t1 t2 x y z roll pitch yaw",
// optionally preceded by the literal word FLOAT (the benchmark's documentation
// writes it; the distributed files omit it). Blank lines and '#' comments are
// skipped; z, roll and pitch are read and ignored (the benchmark is planar).
// Throws InputError naming file:line (and the field) for malformed lines, and
// for a file without any relation.
std::vector<Relation> read_relations(const std::filesystem::path& path);

// Same, from a stream; `source_name` stands for the file name in errors.
std::vector<Relation> read_relations(std::istream& in, const std::string& source_name);

struct RelationMetrics {
  double trans_mean = 0.0;    // metres
  double trans_std = 0.0;     // population standard deviation, metres
  double rot_mean_deg = 0.0;  // degrees
  double rot_std_deg = 0.0;   // population standard deviation, degrees
  std::size_t used = 0;       // relations with an estimated pose at both t1 and t2
  std::size_t missing = 0;    // relations skipped because a timestamp had no pose
  std::vector<double> trans_errors;    // per used relation, in relation order
  std::vector<double> rot_errors_deg;  // per used relation, in relation order
};

// For each relation, the estimated motion δ̂ = p(t1)⁻¹ ⊕ p(t2) is compared with
// the true one δ: error e = δ⁻¹ ⊕ δ̂; translational error ‖(e.x, e.y)‖,
// rotational error |e.theta| in degrees. p(t) is the estimate's pose whose
// timestamp is nearest to t, if within `max_time_diff` seconds; otherwise the
// relation counts as missing. `estimate` need not be sorted by time.
// Throws InputError if no relation can be used (the message gives both time
// spans to show the mismatch), ConfigError for a negative/non-finite max_time_diff.
RelationMetrics evaluate_relations(const Trajectory& estimate, const std::vector<Relation>& relations,
                                   double max_time_diff = 0.001);

}  // namespace dsswarm
