// Units of the scan filter's histogram and correlation, against hand-computed values.
#include "filter/scan_histogram.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace dsswarm {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

LaserScan scan_of(std::vector<float> ranges) {
  LaserScan scan;
  scan.range_min = 0.1;
  scan.range_max = 10.0;
  scan.angle_min = -1.0;
  scan.angle_increment = 0.01;
  scan.ranges = std::move(ranges);
  return scan;
}

HistogramSpec sectors(int columns, HistogramStatistic statistic = HistogramStatistic::median) {
  return {columns, statistic, HistogramBinning::sector};
}

TEST(DefaultColumnCount, FifteenPerThousandBeamsWithinSixToThirty) {
  EXPECT_EQ(default_column_count(1000), 15);
  EXPECT_EQ(default_column_count(1040), 16);
  EXPECT_EQ(default_column_count(700), 11);  // 10.5 rounds up
  EXPECT_EQ(default_column_count(500), 8);
  EXPECT_EQ(default_column_count(400), 6);
  EXPECT_EQ(default_column_count(361), 6);  // mit-csail: 5.4 scaled, raised to the floor
  EXPECT_EQ(default_column_count(360), 6);  // fr079
  EXPECT_EQ(default_column_count(180), 6);  // intel
  EXPECT_EQ(default_column_count(0), 6);
  EXPECT_EQ(default_column_count(2000), 30);
  EXPECT_EQ(default_column_count(5000), 30);
}

TEST(Median, OddEvenAndEmpty) {
  std::vector<double> odd = {3.0, 1.0, 2.0};
  EXPECT_DOUBLE_EQ(median_in_place(odd), 2.0);
  std::vector<double> even = {4.0, 1.0, 3.0, 2.0};
  EXPECT_DOUBLE_EQ(median_in_place(even), 2.5);
  std::vector<double> one = {7.0};
  EXPECT_DOUBLE_EQ(median_in_place(one), 7.0);
  std::vector<double> outlier = {1.0, 1.1, 0.9, 80.0, 1.05};
  EXPECT_DOUBLE_EQ(median_in_place(outlier), 1.05);
  std::vector<double> empty;
  EXPECT_DOUBLE_EQ(median_in_place(empty), 0.0);
}

TEST(Pearson, HandComputed) {
  // x - mean: -2 -1 0 1 2; y - mean: -1 -2 1 0 2; cov 8, var_x 10, var_y 10.
  const std::vector<double> x = {1, 2, 3, 4, 5}, y = {2, 1, 4, 3, 5};
  EXPECT_NEAR(pearson_correlation(x, y), 0.8, 1e-12);
  EXPECT_NEAR(pearson_correlation(y, x), 0.8, 1e-12);
  const std::vector<double> scaled = {12, 22, 32, 42, 52};  // 10 x + 2
  EXPECT_NEAR(pearson_correlation(x, scaled), 1.0, 1e-12);
  const std::vector<double> reversed = {5, 4, 3, 2, 1};
  EXPECT_NEAR(pearson_correlation(x, reversed), -1.0, 1e-12);
  // Orthogonal deviations: -1 1 -1 1 vs -1 -1 1 1.
  EXPECT_NEAR(pearson_correlation(std::vector<double>{0, 2, 0, 2}, std::vector<double>{0, 0, 2, 2}), 0.0, 1e-12);
}

TEST(Pearson, MatchesTheChaptersEquationFive) {
  const std::vector<double> x = {3.1, 4.7, 2.2, 8.9, 5.5, 6.0}, y = {2.9, 5.1, 2.0, 7.5, 6.1, 5.2};
  double sx = 0, sy = 0, sxy = 0, sxx = 0, syy = 0;
  const double n = static_cast<double>(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    sx += x[i], sy += y[i], sxy += x[i] * y[i], sxx += x[i] * x[i], syy += y[i] * y[i];
  }
  const double eq5 = (n * sxy - sx * sy) / std::sqrt((n * sxx - sx * sx) * (n * syy - sy * sy));
  EXPECT_NEAR(pearson_correlation(x, y), eq5, 1e-12);
  EXPECT_GT(eq5, 0.9);
}

TEST(Pearson, DegenerateSeriesGiveOneOrZeroNeverNaN) {
  const std::vector<double> three = {3, 3, 3}, also_three = {3, 3, 3}, four = {4, 4, 4}, varied = {1, 2, 3};
  EXPECT_EQ(pearson_correlation(three, also_three), 1.0);
  EXPECT_EQ(pearson_correlation(three, four), 0.0);
  EXPECT_EQ(pearson_correlation(three, varied), 0.0);
  EXPECT_EQ(pearson_correlation(varied, three), 0.0);
  // Equal up to rounding counts as constant (0.1 summed is not exact).
  const std::vector<double> nearly = {0.1, 0.1 + 1e-15, 0.1 - 1e-15};
  EXPECT_EQ(pearson_correlation(nearly, std::vector<double>{0.1, 0.1, 0.1}), 1.0);
  EXPECT_EQ(pearson_correlation(std::vector<double>{1, 2}, std::vector<double>{1, 2, 3}), 0.0);
  EXPECT_EQ(pearson_correlation(std::vector<double>{}, std::vector<double>{}), 0.0);
}

TEST(ScanHistogram, SectorMedianAndMeanSkipInvalidReadings) {
  // Columns of 3 beams; range_min 0.1, range_max 10.
  const LaserScan scan = scan_of({1, 5, 2, kNaN, 4, kInf, 0.05f, 10, 7});
  EXPECT_EQ(scan_histogram(scan, sectors(3)), (std::vector<double>{2, 4, 7}));
  const std::vector<double> mean = scan_histogram(scan, sectors(3, HistogramStatistic::mean));
  ASSERT_EQ(mean.size(), 3u);
  EXPECT_NEAR(mean[0], 8.0 / 3.0, 1e-12);
  EXPECT_DOUBLE_EQ(mean[1], 4.0);
  EXPECT_DOUBLE_EQ(mean[2], 7.0);
}

TEST(ScanHistogram, UnevenSplitGivesTheRemainderToLaterColumns) {
  // 10 beams in 3 columns: [0,3), [3,6), [6,10).
  const LaserScan scan = scan_of({1, 2, 3, 4, 5, 6, 7, 8, 9, 9.5f});
  EXPECT_EQ(scan_histogram(scan, sectors(3)), (std::vector<double>{2, 5, 8.5}));
}

TEST(ScanHistogram, EmptySectorGetsTheScansMedianRange) {
  // Valid ranges 1 3 5 7: median 4 for the all-invalid middle sector.
  const LaserScan scan = scan_of({1, 3, kNaN, 10, 5, 7});
  EXPECT_EQ(scan_histogram(scan, sectors(3)), (std::vector<double>{2, 4, 6}));
}

TEST(ScanHistogram, NoValidBeamGivesZerosAndFewBeamsOneColumnEach) {
  const LaserScan blind = scan_of({kNaN, kInf, 0, 10, 50, -1});
  EXPECT_EQ(scan_histogram(blind, sectors(3)), (std::vector<double>{0, 0, 0}));
  EXPECT_EQ(scan_histogram(scan_of({}), sectors(4)), (std::vector<double>{0, 0, 0, 0}));
  EXPECT_EQ(scan_histogram(scan_of({2, 3}), sectors(30)), (std::vector<double>{2, 3}));
}

TEST(ScanHistogram, DistanceBinningCountsPointsPerRangeInterval) {
  // Valid 1 2 3 4 5 9 -> [1, 9] in 4 intervals of 2 m; 9 falls in the last one.
  const LaserScan scan = scan_of({1, 2, kNaN, 3, 4, 5, 9, 12, 0});
  const HistogramSpec spec{4, HistogramStatistic::median, HistogramBinning::distance};
  EXPECT_EQ(scan_histogram(scan, spec), (std::vector<double>{2, 2, 1, 1}));
  // All the same range: everything in the first column.
  EXPECT_EQ(scan_histogram(scan_of({3, 3, 3}), spec), (std::vector<double>{3, 0, 0, 0}));
  EXPECT_EQ(scan_histogram(scan_of({kNaN}), spec), (std::vector<double>{0, 0, 0, 0}));
}

}  // namespace
}  // namespace dsswarm
