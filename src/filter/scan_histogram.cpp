#include "filter/scan_histogram.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace dsswarm {

int default_column_count(std::size_t beams) {
  const double scaled = std::round(15.0 * static_cast<double>(beams) / 1000.0);
  return static_cast<int>(std::clamp(scaled, 6.0, 30.0));
}


namespace {

double statistic_of(std::span<double> values, HistogramStatistic statistic) {
  if (statistic == HistogramStatistic::median) return median_in_place(values);
  return std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
}

std::vector<double> sector_histogram(const LaserScan& scan, std::size_t columns, HistogramStatistic statistic,
                                     std::span<double> valid_ranges) {
  const std::size_t n = scan.ranges.size();
  const double empty_value = median_in_place(valid_ranges);
  std::vector<double> histogram(columns, empty_value);
  std::vector<double> sector;
  for (std::size_t c = 0; c < columns; ++c) {
    sector.clear();
    for (std::size_t i = c * n / columns; i < (c + 1) * n / columns; ++i) {
      if (scan.is_valid(scan.ranges[i])) sector.push_back(scan.ranges[i]);
    }
    if (!sector.empty()) histogram[c] = statistic_of(sector, statistic);
  }
  return histogram;
}

std::vector<double> distance_histogram(std::size_t columns, std::span<const double> valid_ranges) {
  std::vector<double> histogram(columns, 0.0);
  if (valid_ranges.empty()) return histogram;
  const auto [lo_it, hi_it] = std::minmax_element(valid_ranges.begin(), valid_ranges.end());
  const double lo = *lo_it, span = *hi_it - *lo_it;
  const double b = static_cast<double>(columns);
  for (double r : valid_ranges) {
    // The largest range lands in the last column, not one past it.
    const double position = span > 0.0 ? std::min((r - lo) / span * b, b - 1.0) : 0.0;
    histogram[static_cast<std::size_t>(position)] += 1.0;
  }
  return histogram;
}

// Equal within a relative tolerance: float ranges summed and divided are not
// bit-exact, and a "constant" series must not yield a noise correlation.
double tolerance_for(std::span<const double> a) {
  double largest = 1.0;
  for (double v : a) largest = std::max(largest, std::abs(v));
  return 1e-9 * largest;
}

bool is_constant(std::span<const double> a, double tolerance) {
  const auto [lo, hi] = std::minmax_element(a.begin(), a.end());
  return *hi - *lo <= tolerance;
}

}  // namespace

std::vector<double> scan_histogram(const LaserScan& scan, const HistogramSpec& spec) {
  const std::size_t n = scan.ranges.size();
  const std::size_t wanted = static_cast<std::size_t>(std::max(spec.columns, 1));
  std::vector<double> valid_ranges;
  valid_ranges.reserve(n);
  for (float r : scan.ranges) {
    if (scan.is_valid(r)) valid_ranges.push_back(r);
  }
  if (spec.binning == HistogramBinning::distance) return distance_histogram(wanted, valid_ranges);
  const std::size_t columns = n == 0 ? wanted : std::min(wanted, n);
  return sector_histogram(scan, columns, spec.statistic, valid_ranges);
}

double pearson_correlation(std::span<const double> a, std::span<const double> b) {
  if (a.size() != b.size() || a.empty()) return 0.0;
  const double tolerance = std::max(tolerance_for(a), tolerance_for(b));
  const bool a_constant = is_constant(a, tolerance), b_constant = is_constant(b, tolerance);
  if (a_constant || b_constant) {
    return a_constant && b_constant && std::abs(a[0] - b[0]) <= tolerance ? 1.0 : 0.0;
  }
  const double count = static_cast<double>(a.size());
  const double mean_a = std::accumulate(a.begin(), a.end(), 0.0) / count;
  const double mean_b = std::accumulate(b.begin(), b.end(), 0.0) / count;
  double cov = 0.0, var_a = 0.0, var_b = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double da = a[i] - mean_a, db = b[i] - mean_b;
    cov += da * db;
    var_a += da * da;
    var_b += db * db;
  }
  return std::clamp(cov / std::sqrt(var_a * var_b), -1.0, 1.0);
}

}  // namespace dsswarm
