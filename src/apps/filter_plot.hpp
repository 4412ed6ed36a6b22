#pragma once
// The picture `dsswarm filter --plot` writes: the scan filter's decisions over
// the scans of a log, with axes, labels and a legend.
#include <vector>

#include "filter/scan_filter.hpp"
#include "io/maps/render.hpp"

namespace dsswarm {

struct DecisionRow {
  double timestamp = 0.0;
  ScanFilter::Decision decision;
};

// One column per scan (or per group of scans on long logs), scan index on
// the x axis. Top panel: the smallest correlation with the window, 0.8 to 1.0,
// P_pair (`pair_threshold`) as a blue line; kept scans dark grey, dropped red.
// Bottom band: the share of each column's scans that were dropped (white to
// red) and the drop ratio over the last 100 scans (black line), 0 to 1.
Image filter_plot(const std::vector<DecisionRow>& rows, double pair_threshold);

}  // namespace dsswarm
