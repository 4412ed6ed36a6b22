#pragma once
// Median by partial sort (O(n)); reorders `values`. The mean of the two middle
// values for an even count; 0 for an empty span (callers that care check first).
#include <algorithm>
#include <cstddef>
#include <span>

namespace dsswarm {

inline double median_in_place(std::span<double> values) {
  if (values.empty()) return 0.0;
  const std::size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(mid), values.end());
  const double upper = values[mid];
  if (values.size() % 2 == 1) return upper;
  // After nth_element everything before `mid` is <= upper; the lower middle is their maximum.
  const double lower = *std::max_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(mid));
  return 0.5 * (lower + upper);
}

}  // namespace dsswarm
