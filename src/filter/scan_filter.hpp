#pragma once
// The laser-scan filter of the chapter (section 4): a scan that correlates
// strongly with every scan in a sliding window of recently kept scans adds
// nothing new and is dropped before matching. Scans are summarized by small
// histograms (filter/scan_histogram.hpp) and compared by Pearson correlation.
//
// Per scan: histogram h (O(n)); window size W from the robot's speed; the
// Pearson correlation of h with each of the newest W kept histograms (O(W B)).
// Drop when every correlation >= P_pair and their product >= P_common, unless
// a safety valve keeps the scan (window not full yet, moved or turned too much
// since the last kept scan, too many drops in a row).
#include <cstddef>
#include <deque>
#include <optional>
#include <vector>

#include "filter/scan_histogram.hpp"
#include "geometry/pose2.hpp"
#include "sensor/laser_scan.hpp"

namespace dsswarm {

struct ScanFilterConfig {
  // Histogram columns B. 0 = default_column_count(beams): 30 for ~1000 beams
  // as in the chapter, scaled with the beam count, within [15, 30].
  int columns = 0;
  HistogramStatistic statistic = HistogramStatistic::median;  // sector binning only
  HistogramBinning binning = HistogramBinning::sector;

  // P_pair: every correlation with the window must reach it to drop. The
  // chapter: at least 0.95, better 0.98. Allowed [0.95, 0.99].
  double pair_threshold = 0.98;
  // P_common: the product of the correlations must reach it to drop. Unset =
  // pair_threshold^W, the chapter's example (0.98^5 = 0.904); with that
  // default the pairwise test already implies it, so set it only to be stricter.
  std::optional<double> common_threshold;

  // Window size W = window_constant / v^2 (chapter eq. 7), v = mean odometry
  // travel per scan in centimetres over the last speed_samples scans; rounded
  // and clamped to [min_window, max_window] (a standing robot would otherwise
  // get an infinite window). fixed_window when there is no odometry.
  double window_constant = 27.0;
  int min_window = 2;
  int max_window = 10;
  int fixed_window = 5;
  int speed_samples = 20;

  // Safety valves: never more drops in a row than this (the authors' code: 10;
  // 0 disables the filter), and never drop once odometry says the robot moved
  // or turned more than this since the last kept scan (metres, radians).
  int max_consecutive_drops = 10;
  double max_translation = 0.25;
  double max_rotation = 0.2;

  // Throws ConfigError naming the first field out of range.
  void validate() const;
};

class ScanFilter {
 public:
  struct Decision {
    bool keep = true;
    double min_correlation = 0.0;  // smallest correlation with the window; 0 when the window is empty
    double product = 0.0;          // product of those correlations; 0 when the window is empty
    int window = 0;                // W used for this scan
    const char* reason = "";       // kept: window_filling, dissimilar, moved, drop_cap; dropped: similar
  };

  explicit ScanFilter(const ScanFilterConfig& config = {});  // validates `config`

  // Decides one scan; call in sensor order. A kept scan joins the window.
  Decision decide(const LaserScan& scan);

  std::size_t kept() const { return kept_; }
  std::size_t dropped() const { return dropped_; }
  // Current estimate of v (cm per scan); nullopt before two scans with odometry.
  std::optional<double> speed_cm_per_scan() const;
  const ScanFilterConfig& config() const { return config_; }

 private:
  void record_travel(const LaserScan& scan);
  int window_size(bool has_odometry) const;
  bool moved_since_last_kept(const LaserScan& scan) const;

  ScanFilterConfig config_;
  std::deque<std::vector<double>> window_;  // histograms of the newest kept scans, oldest first
  std::optional<Pose2> last_kept_odometry_;
  std::optional<Pose2> previous_odometry_;  // of the previous scan, kept or not
  std::deque<double> travel_;               // metres between consecutive scans, newest last
  int consecutive_drops_ = 0;
  std::size_t kept_ = 0;
  std::size_t dropped_ = 0;
};

}  // namespace dsswarm
