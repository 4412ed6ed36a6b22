#pragma once
// The best a joint frame could do, found in hindsight: where agent Y's
// trajectory would have to sit in agent X's frame to reproduce their cross
// relations best. Scoring the cross relations there tells what of the
// cross-agent error is the frame the swarm estimated (at encounters, against
// the maps as they stood) and what is the two maps disagreeing with each other,
// which no frame can remove.
//
// A cross relation's translational error is a distance between two points:
// with t1 on X and t2 on Y it is ‖(x(t1) ⊕ δ).t − (T ⊕ y(t2)).t‖ (the
// rotation in front of it keeps lengths), and the same the other way round.
// So the least-squares T is a rigid fit of point pairs, in closed form.
#include <optional>
#include <vector>

#include "eval/relations.hpp"
#include "geometry/pose2.hpp"
#include "io/trajectory/tum.hpp"

namespace dsswarm {

// Y's frame in X's (T with x ≈ T ⊕ y) from the relations with one end on each
// (pose within max_time_diff); none when fewer than two such relations.
// Throws InputError for non-finite poses.
std::optional<Pose2> fit_cross_frame(const Trajectory& x, const Trajectory& y, const std::vector<Relation>& relations,
                                     double max_time_diff);

}  // namespace dsswarm
