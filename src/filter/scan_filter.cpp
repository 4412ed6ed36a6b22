#include "filter/scan_filter.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <sstream>
#include <utility>

#include "common/errors.hpp"

namespace dsswarm {

namespace {

void require(bool ok, const char* field, const char* rule, double value) {
  if (ok) return;
  std::ostringstream message;
  message << "scan filter: " << field << " must be " << rule << ", got " << value;
  throw ConfigError(message.str());
}

}  // namespace

void ScanFilterConfig::validate() const {
  // With 2 columns every Pearson correlation is +-1; 3 is the least that can tell scans apart.
  require(columns == 0 || (columns >= 3 && columns <= 4096), "columns", "0 (automatic) or in [3, 4096]", columns);
  require(pair_threshold >= 0.95 && pair_threshold <= 0.99, "pair_threshold", "in [0.95, 0.99]", pair_threshold);
  if (common_threshold) {
    require(*common_threshold > 0.0 && *common_threshold <= 1.0, "common_threshold", "in (0, 1]", *common_threshold);
  }
  require(window_constant > 0.0 && std::isfinite(window_constant), "window_constant", "finite and > 0",
          window_constant);
  require(min_window >= 1 && min_window <= 100, "min_window", "in [1, 100]", min_window);
  require(max_window >= min_window && max_window <= 100, "max_window", "in [min_window, 100]", max_window);
  require(fixed_window >= 1 && fixed_window <= 100, "fixed_window", "in [1, 100]", fixed_window);
  require(speed_samples >= 1 && speed_samples <= 10000, "speed_samples", "in [1, 10000]", speed_samples);
  require(max_consecutive_drops >= 0 && max_consecutive_drops <= 1000, "max_consecutive_drops", "in [0, 1000]",
          max_consecutive_drops);
  // +inf is accepted: "no limit".
  require(max_translation > 0.0, "max_translation", "> 0 (metres)", max_translation);
  require(max_rotation > 0.0, "max_rotation", "> 0 (radians)", max_rotation);
  require(doubt_ratio >= 0.0, "doubt_ratio", ">= 0 (+inf disables)", doubt_ratio);
  require(doubt_min_travel >= 0.0 && std::isfinite(doubt_min_travel), "doubt_min_travel", "finite and >= 0 (metres)",
          doubt_min_travel);
  require(doubt_cone > 0.0 && doubt_cone <= std::numbers::pi, "doubt_cone", "in (0, pi] (radians)", doubt_cone);
}

ScanFilter::ScanFilter(const ScanFilterConfig& config) : config_(config) { config_.validate(); }

std::optional<double> ScanFilter::speed_cm_per_scan() const {
  if (travel_.empty()) return std::nullopt;
  const double sum = std::accumulate(travel_.begin(), travel_.end(), 0.0);
  return 100.0 * sum / static_cast<double>(travel_.size());
}

void ScanFilter::record_travel(const LaserScan& scan) {
  if (scan.odometry && previous_odometry_) {
    travel_.push_back(std::hypot(scan.odometry->x - previous_odometry_->x, scan.odometry->y - previous_odometry_->y));
    if (travel_.size() > static_cast<std::size_t>(config_.speed_samples)) travel_.pop_front();
  }
  previous_odometry_ = scan.odometry;
}

int ScanFilter::window_size(bool has_odometry) const {
  const std::optional<double> v = speed_cm_per_scan();
  if (!has_odometry || !v) return config_.fixed_window;
  // A standing robot (v = 0) gets the largest window, not a division by zero.
  const double size = *v > 0.0 ? std::round(config_.window_constant / (*v * *v)) : config_.max_window;
  return static_cast<int>(std::clamp(size, double(config_.min_window), double(config_.max_window)));
}

bool ScanFilter::moved_since_last_kept(const LaserScan& scan) const {
  if (!scan.odometry || !last_kept_odometry_) return false;
  const Pose2 motion = between(*last_kept_odometry_, *scan.odometry);
  return std::hypot(motion.x, motion.y) > config_.max_translation || std::abs(motion.theta) > config_.max_rotation;
}

bool ScanFilter::odometry_contradicted(const LaserScan& scan) const {
  if (!std::isfinite(config_.doubt_ratio)) return false;
  if (!scan.odometry || !last_kept_odometry_ || last_kept_ranges_.size() != scan.ranges.size()) return false;
  const double forward = between(*last_kept_odometry_, *scan.odometry).x;
  if (std::abs(forward) < config_.doubt_min_travel) return false;
  // Beam by beam, not by histogram column: the test must not get coarser
  // when the histogram has few columns.
  std::vector<double> ahead;
  for (std::size_t i = 0; i < scan.ranges.size(); ++i) {
    const double bearing = normalize_angle(scan.beam_angle(i) + scan.laser_offset.theta);
    if (std::abs(bearing) > config_.doubt_cone) continue;
    const float now = scan.ranges[i], then = last_kept_ranges_[i];
    if (scan.is_valid(now) && scan.is_valid(then)) ahead.push_back(static_cast<double>(now) - then);
  }
  if (ahead.empty()) return false;
  // Positive: the view ahead receded while odometry claims approach (or the reverse).
  const double against = (forward > 0.0 ? 1.0 : -1.0) * median_in_place(ahead);
  return against > config_.doubt_ratio * std::abs(forward);
}

ScanFilter::Decision ScanFilter::decide(const LaserScan& scan) {
  HistogramSpec spec{config_.columns, config_.statistic, config_.binning};
  if (spec.columns == 0) spec.columns = default_column_count(scan.ranges.size());
  std::vector<double> histogram = scan_histogram(scan, spec);

  record_travel(scan);
  Decision d;
  d.window = window_size(scan.odometry.has_value());

  // Compare with the newest W kept histograms (all of them while fewer are stored).
  const std::size_t compared = std::min(window_.size(), static_cast<std::size_t>(d.window));
  if (compared > 0) {
    d.min_correlation = 1.0;
    d.product = 1.0;
    for (auto it = window_.end() - static_cast<std::ptrdiff_t>(compared); it != window_.end(); ++it) {
      const double r = pearson_correlation(histogram, *it);
      d.min_correlation = std::min(d.min_correlation, r);
      d.product *= r;
    }
  }
  const double common = config_.common_threshold.value_or(std::pow(config_.pair_threshold, d.window));

  if (compared < static_cast<std::size_t>(d.window)) {
    d.reason = "window_filling";
  } else if (d.min_correlation < config_.pair_threshold || d.product < common) {
    d.reason = "dissimilar";
  } else if (moved_since_last_kept(scan)) {
    d.reason = "moved";
  } else if (odometry_contradicted(scan)) {
    d.reason = "odometry_doubt";
  } else if (consecutive_drops_ >= config_.max_consecutive_drops) {
    d.reason = "drop_cap";
  } else {
    d.keep = false;
    d.reason = "similar";
  }

  if (d.keep) {
    window_.push_back(std::move(histogram));
    // Keep enough history for the largest window the speed may ask for later.
    while (window_.size() > static_cast<std::size_t>(std::max(config_.max_window, config_.fixed_window))) {
      window_.pop_front();
    }
    last_kept_odometry_ = scan.odometry;
    last_kept_ranges_ = scan.ranges;
    consecutive_drops_ = 0;
    ++kept_;
  } else {
    ++consecutive_drops_;
    ++dropped_;
  }
  return d;
}

}  // namespace dsswarm
