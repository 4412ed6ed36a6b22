#pragma once
// The compact summary the scan filter compares instead of raw scans: a
// histogram of a few columns per scan (chapter section 4), and the Pearson
// correlation between two such histograms. O(n) per scan, O(B) per pair.
#include <cstddef>
#include <span>
#include <vector>

#include "common/median.hpp"
#include "sensor/laser_scan.hpp"

namespace dsswarm {

enum class HistogramStatistic { median, mean };

enum class HistogramBinning {
  // Column c holds the statistic of the valid ranges of beams
  // [c*n/B, (c+1)*n/B): one angular sector per column. A rotation shifts the
  // histogram, so it decorrelates quickly (what the filter wants).
  sector,
  // The chapter's literal first wording: column c counts the valid ranges that
  // fall in the c-th of B equal intervals between the scan's smallest and
  // largest valid range. Blind to rotation; `statistic` is not used.
  distance,
};

struct HistogramSpec {
  int columns = 30;  // B >= 1
  HistogramStatistic statistic = HistogramStatistic::median;
  HistogramBinning binning = HistogramBinning::sector;
};

// The default column count for an n-beam scan: 15 columns per 1000 beams,
// the lower of the chapter's two choices for its ~1000-beam lidar ("15 or
// 30"), within [6, 30]: 6 for the 180-361 beams of our logs (30-degree
// sectors), 15 for 1000 beams, 30 from 2000. Why the lower one: the chapter's
// logs ran at 10-40 Hz, ours are thinned to 5 Hz (4-19 cm between scans), so
// consecutive scans differ more and every extra column makes the correlation
// stricter. Measured (README, "Scan filter"): 11 columns (30 per 1000) left
// mit-csail only 29-33% of its scans to drop, 6 columns 40%, at the same
// accuracy; the floor of 6 keeps rotations visible (a 0.2 rad turn shifts a
// 30-degree sector by a third).
int default_column_count(std::size_t beams);

// The histogram of `scan` (see HistogramBinning). Invalid readings (NaN, inf,
// <= range_min, >= range_max) are skipped. A sector without any valid beam
// gets the median of the scan's valid ranges: a neutral value that adds
// (almost) nothing to the correlation, where range_max would be an outlier
// dominating every correlation. A scan without any valid beam gives all
// zeros. Fewer beams than columns: one column per beam. Never NaN.
std::vector<double> scan_histogram(const LaserScan& scan, const HistogramSpec& spec);

// Pearson correlation coefficient of two equally long, finite series, in [-1, 1]
// (computed about the means, which equals the chapter's eq. 5 but does not
// cancel catastrophically). Degenerate cases, never NaN:
//   - a constant series has no defined correlation; two constant series that
//     are equal count as identical (1), otherwise 0 (nothing in common);
//   - different lengths or empty series: 0.
double pearson_correlation(std::span<const double> a, std::span<const double> b);

}  // namespace dsswarm
