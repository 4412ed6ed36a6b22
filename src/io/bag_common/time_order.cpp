#include "io/bag_common/time_order.hpp"

#include <algorithm>
#include <cassert>

namespace dsswarm {

std::size_t count_backward_steps(std::span<const double> stamps) {
  std::size_t n = 0;
  for (std::size_t i = 1; i < stamps.size(); ++i) n += stamps[i] < stamps[i - 1] ? 1 : 0;
  return n;
}

std::vector<bool> longest_nondecreasing(std::span<const double> stamps) {
  // Patience method: tail_index[k] is the record ending the best subsequence
  // of length k + 1 found so far (whose stamps tail_stamps[k] are sorted).
  constexpr std::size_t kNone = static_cast<std::size_t>(-1);
  std::vector<double> tail_stamps;
  std::vector<std::size_t> tail_index;
  std::vector<std::size_t> previous(stamps.size(), kNone);
  for (std::size_t i = 0; i < stamps.size(); ++i) {
    const auto pos = std::upper_bound(tail_stamps.begin(), tail_stamps.end(), stamps[i]);
    const auto k = static_cast<std::size_t>(pos - tail_stamps.begin());
    if (k > 0) previous[i] = tail_index[k - 1];
    if (k == tail_stamps.size()) {
      tail_stamps.push_back(stamps[i]);
      tail_index.push_back(i);
    } else {
      tail_stamps[k] = stamps[i];
      tail_index[k] = i;
    }
  }
  std::vector<bool> member(stamps.size(), false);
  for (std::size_t i = tail_index.empty() ? kNone : tail_index.back(); i != kNone;
       i = previous[i]) {
    member[i] = true;
  }
  return member;
}

std::vector<double> lookup_times(std::span<const double> stamps,
                                 const std::vector<bool>& in_order) {
  assert(in_order.size() == stamps.size());
  std::vector<double> times(stamps.begin(), stamps.end());
  std::size_t before = stamps.size();  // last in-order record seen (none yet)
  for (std::size_t i = 0; i < stamps.size(); ++i) {
    if (in_order[i]) {
      before = i;
      continue;
    }
    std::size_t after = i + 1;
    while (after < stamps.size() && !in_order[after]) ++after;
    if (before == stamps.size()) {
      times[i] = stamps[after];
    } else if (after == stamps.size()) {
      times[i] = stamps[before];
    } else {
      const double u = static_cast<double>(i - before) / static_cast<double>(after - before);
      times[i] = stamps[before] + u * (stamps[after] - stamps[before]);
    }
  }
  return times;
}

}  // namespace dsswarm
