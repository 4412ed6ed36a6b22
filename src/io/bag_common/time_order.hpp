#pragma once
// Making sense of timestamps that do not follow the file order.
//
// In the intel log about 5% of the records carry a stamp that jumps ahead of
// its neighbours (by up to 0.9 s) while the file order is the true order. The
// records that agree with the file order are the longest run of
// non-decreasing stamps; the others are the glitches. Interpolating odometry
// through a glitched odometry record, or at a glitched scan stamp, would put
// the robot up to a metre away from where it was.
#include <cstddef>
#include <span>
#include <vector>

namespace dsswarm {

// Number of i with stamps[i] < stamps[i - 1].
std::size_t count_backward_steps(std::span<const double> stamps);

// Marks the members of a longest non-decreasing subsequence of `stamps`
// (O(n log n)). Where several are equally long, the choice is the one the
// CARMEN logs in ../shared/data were converted with (checked on all three),
// so odometry looked up here agrees with their odom_* fields.
std::vector<bool> longest_nondecreasing(std::span<const double> stamps);

// The time at which to look a record up: its own stamp when `in_order[i]`,
// otherwise a time interpolated by file position between the nearest in-order
// records before and after it (the nearest one's stamp at either end).
// `in_order` must have the size of `stamps` and at least one true entry.
std::vector<double> lookup_times(std::span<const double> stamps, const std::vector<bool>& in_order);

}  // namespace dsswarm
