#include "apps/filter_plot.hpp"

#include <gtest/gtest.h>

namespace dsswarm {
namespace {

// Pixels of `colour` in the rectangle [x0, x1) × [y0, y1).
int count_in(const Image& img, int x0, int y0, int x1, int y1, Rgb colour) {
  int n = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) n += img.at(x, y) == colour ? 1 : 0;
  return n;
}

std::vector<DecisionRow> alternating(std::size_t n) {
  std::vector<DecisionRow> rows(n);
  for (std::size_t i = 0; i < n; ++i) {
    rows[i].timestamp = static_cast<double>(i);
    rows[i].decision.keep = i % 3 != 0;
    rows[i].decision.min_correlation = rows[i].decision.keep ? 0.9 : 0.97;
  }
  return rows;
}

// Without labels the picture is a pattern of dots; with them a person can
// read it: tick labels left of the panels and under the x axis, a legend above.
TEST(FilterPlot, HasAxisLabelsAndALegend) {
  const Image img = filter_plot(alternating(1234), 0.95);
  ASSERT_EQ(img.width, 1600);
  const Rgb ink{0, 0, 0}, dropped{220, 40, 40}, kept{70, 70, 70}, threshold{40, 90, 220};
  EXPECT_GT(count_in(img, 0, 40, 80, img.height - 60, ink), 200) << "no y tick labels or axis titles";
  EXPECT_GT(count_in(img, 80, img.height - 50, img.width, img.height, ink), 200) << "no x tick labels";
  EXPECT_GT(count_in(img, 0, 0, img.width, 40, dropped), 0) << "no legend entry for dropped scans";
  EXPECT_GT(count_in(img, 0, 0, img.width, 40, kept), 0) << "no legend entry for kept scans";
  EXPECT_GT(count_in(img, 0, 0, img.width, 40, threshold), 0) << "no legend entry for P_pair";
  EXPECT_GT(count_in(img, 0, 0, img.width, 40, ink), 500) << "no legend text";
}

TEST(FilterPlot, EmptyAndTinyLogsDrawWithoutTrouble) {
  EXPECT_EQ(filter_plot({}, 0.95).width, 1600);
  EXPECT_EQ(filter_plot(alternating(1), 0.99).width, 1600);
}

}  // namespace
}  // namespace dsswarm
