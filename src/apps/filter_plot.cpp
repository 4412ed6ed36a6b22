#include "apps/filter_plot.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>

#include "io/maps/annotate.hpp"

namespace dsswarm {
namespace {

constexpr int kWidth = 1600;
constexpr int kText = 2;                                   // label scale
constexpr int kLeft = 90, kRight = 20, kTop = 50;          // margins
constexpr int kPanel = 360, kGap = 40, kBand = 80, kBottom = 60;
constexpr int kPlotWidth = kWidth - kLeft - kRight;
constexpr int kPanelTop = kTop, kBandTop = kTop + kPanel + kGap;
constexpr double kLowest = 0.8;                            // bottom of the correlation axis
constexpr std::size_t kRunning = 100;                      // scans in the running drop ratio

constexpr Rgb kKept{70, 70, 70}, kDropped{220, 40, 40}, kThreshold{40, 90, 220};
constexpr Rgb kGrid{225, 225, 225}, kInk{0, 0, 0}, kPaper{255, 255, 255};

int panel_y(double correlation) {
  const double t = std::clamp((correlation - kLowest) / (1.0 - kLowest), 0.0, 1.0);
  return kPanelTop + static_cast<int>(std::lround((1.0 - t) * (kPanel - 1)));
}

int band_y(double share) {
  return kBandTop + static_cast<int>(std::lround((1.0 - std::clamp(share, 0.0, 1.0)) * (kBand - 1)));
}

// Per column: scans and drops in it, and the running drop ratio at its last scan (-1: no scan).
struct Columns {
  std::vector<int> scans = std::vector<int>(kPlotWidth, 0), drops = std::vector<int>(kPlotWidth, 0);
  std::vector<double> running = std::vector<double>(kPlotWidth, -1.0);
};

int column_of(std::size_t i, std::size_t n) {
  return static_cast<int>(static_cast<double>(i) * kPlotWidth / static_cast<double>(std::max<std::size_t>(n, 1)));
}

Columns draw_scans(Image& img, const std::vector<DecisionRow>& rows) {
  Columns c;
  std::size_t recent_drops = 0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const int x = column_of(i, rows.size());
    const ScanFilter::Decision& d = rows[i].decision;
    fill_rect(img, kLeft + x, panel_y(d.min_correlation) - 1, 1, 3, d.keep ? kKept : kDropped);
    ++c.scans[x];
    if (!d.keep) ++c.drops[x], ++recent_drops;
    if (i >= kRunning && !rows[i - kRunning].decision.keep) --recent_drops;
    c.running[x] = static_cast<double>(recent_drops) / static_cast<double>(std::min(i + 1, kRunning));
  }
  return c;
}

void draw_band(Image& img, const Columns& c) {
  for (int x = 0; x < kPlotWidth; ++x) {
    if (c.scans[x] == 0) continue;
    const double share = static_cast<double>(c.drops[x]) / c.scans[x];
    auto mix = [share](int red) { return static_cast<std::uint8_t>(std::lround(255 + share * (red - 255))); };
    fill_rect(img, kLeft + x, kBandTop, 1, kBand, Rgb{mix(kDropped.r), mix(kDropped.g), mix(kDropped.b)});
    img.at(kLeft + x, band_y(0.5)) = kGrid;
  }
  int last_y = -1;
  for (int x = 0; x < kPlotWidth; ++x) {
    if (c.running[x] < 0.0) continue;
    const int y = band_y(c.running[x]);
    const int from = last_y < 0 ? y : std::min(y, last_y), to = last_y < 0 ? y : std::max(y, last_y);
    fill_rect(img, kLeft + x, from, 1, to - from + 1, kInk);
    last_y = y;
  }
}

// 1, 2 or 5 × 10^k: at most ten ticks over n scans.
std::size_t tick_step(std::size_t n) {
  for (std::size_t decade = 1;; decade *= 10)
    for (std::size_t m : {1, 2, 5})
      if (n <= 10 * m * decade) return m * decade;
}

// A y tick label right-aligned against the axis, centred on `y`.
void y_label(Image& img, int y, const std::string& text) {
  draw_text(img, kLeft - 8 - text_width(text, kText), y - text_height(kText) / 2, text, kInk, kText);
  fill_rect(img, kLeft - 5, y, 5, 1, kInk);
}

void draw_axes(Image& img, std::size_t scans, double pair_threshold) {
  for (int g = 0; g <= 4; ++g) {
    const double c = kLowest + 0.05 * g;
    fill_rect(img, kLeft, panel_y(c), kPlotWidth, 1, kGrid);
    y_label(img, panel_y(c), fmt::format("{:.2f}", c));
  }
  fill_rect(img, kLeft, panel_y(pair_threshold), kPlotWidth, 1, kThreshold);
  for (double share : {0.0, 0.5, 1.0}) y_label(img, band_y(share), fmt::format("{}", share));
  fill_rect(img, kLeft - 1, kPanelTop, 1, kPanel, kInk);  // y axes
  fill_rect(img, kLeft - 1, kBandTop, 1, kBand, kInk);
  const int axis_y = kBandTop + kBand + 2;
  fill_rect(img, kLeft, axis_y, kPlotWidth, 1, kInk);  // x axis: scan index, ticks at round numbers
  const std::size_t step = tick_step(scans);
  for (std::size_t i = 0; i < std::max<std::size_t>(scans, 1); i += step) {
    const int x = kLeft + column_of(i, scans);
    const std::string label = fmt::format("{}", i);
    fill_rect(img, x, axis_y, 1, 6, kInk);
    draw_text(img, x - text_width(label, kText) / 2, axis_y + 10, label, kInk, kText);
  }
  const std::string x_title = "scan index";
  draw_text(img, kLeft + kPlotWidth - text_width(x_title, kText), axis_y + 18 + text_height(kText), x_title, kInk,
            kText);
  // Axis titles read upwards, centred on their panel.
  for (const auto& [title, top, height] : {std::tuple{"min correlation", kPanelTop, kPanel},
                                           std::tuple{"dropped", kBandTop, kBand}})
    draw_text_up(img, 12, top + height / 2 + text_width(title, kText) / 2, title, kInk, kText);
}

void draw_legends(Image& img, double pair_threshold) {
  const std::string title = "smallest correlation of each scan with the window:";
  const int top = (kTop - text_height(kText)) / 2;
  draw_text(img, kLeft, top, title, kInk, kText);
  int x = kLeft + text_width(title, kText) + 20;
  for (const LegendEntry& e : {LegendEntry{"kept", kKept, LegendEntry::Mark::Disc},
                               LegendEntry{"dropped", kDropped, LegendEntry::Mark::Disc},
                               LegendEntry{fmt::format("P_pair {}", pair_threshold), kThreshold}})
    x += draw_legend_entry(img, x, top, e, kText) + 30;
  x = kLeft;
  const int band_top = kBandTop - kGap / 2 - text_height(kText) / 2;
  for (const LegendEntry& e : {LegendEntry{"share of the scans in a column that were dropped", kDropped},
                               LegendEntry{fmt::format("drop ratio over the last {} scans", kRunning), kInk}})
    x += draw_legend_entry(img, x, band_top, e, kText) + 30;
}

}  // namespace

Image filter_plot(const std::vector<DecisionRow>& rows, double pair_threshold) {
  Image img{kWidth, kBandTop + kBand + kBottom, {}};
  img.pixels.assign(static_cast<std::size_t>(img.width) * img.height, kPaper);
  draw_axes(img, rows.size(), pair_threshold);
  draw_band(img, draw_scans(img, rows));
  draw_legends(img, pair_threshold);
  return img;
}

}  // namespace dsswarm
