#include "apps/filter_command.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ostream.h>
#include <nlohmann/json.hpp>

#include "common/errors.hpp"
#include "filter/scan_filter.hpp"
#include "io/atomic_file.hpp"
#include "io/logs/carmen_writer.hpp"
#include "io/logs/log_reader.hpp"
#include "io/maps/render.hpp"

namespace dsswarm {

namespace {

// Option storage must outlive add_filter_command(): CLI11 writes into it
// during parsing, and the callback (which owns it through the shared_ptr) reads it.
struct FilterArgs {
  std::string log;
  std::string out;
  std::string decisions;
  std::string plot;
  std::string scan_topic = "/scan";
  std::string odom_topic = "/odom";
  bool no_odometry = false;
  std::string statistic = "median";
  std::string binning = "sector";
  std::optional<double> common_threshold;
  ScanFilterConfig config;
};

struct DecisionRow {
  double timestamp;
  ScanFilter::Decision decision;
};

void write_decisions(const std::string& path, const std::vector<DecisionRow>& rows) {
  write_file_atomically(path, [&rows](std::ostream& out) {
    out << "index,timestamp,kept,min_correlation,product,window,reason\n";
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const ScanFilter::Decision& d = rows[i].decision;
      fmt::print(out, "{},{},{},{:.6f},{:.6f},{},{}\n", i, rows[i].timestamp, d.keep ? 1 : 0, d.min_correlation,
                 d.product, d.window, d.reason);
    }
  });
}

// A picture of the filter over time: one column per scan (or per group of
// scans on long logs). Top panel: the smallest correlation with the window,
// from 0.8 (bottom) to 1.0 (top), with P_pair as a blue line; kept scans in
// dark grey, dropped scans in red. Bottom band: the share of each column's
// scans that were dropped, from white (none) to red (all), and in black the
// drop ratio over the last 100 scans (bottom 0, top 1; grey line at 0.5).
void write_plot(const std::string& path, const std::vector<DecisionRow>& rows, double pair_threshold) {
  constexpr int kWidth = 1600, kPanel = 360, kBand = 60, kGap = 10;
  constexpr std::size_t kRunning = 100;
  Image img{kWidth, kPanel + kGap + kBand, {}};
  img.pixels.assign(static_cast<std::size_t>(img.width) * img.height, Rgb{255, 255, 255});
  const Rgb kept{70, 70, 70}, dropped{220, 40, 40}, threshold{40, 90, 220}, grid{225, 225, 225}, ink{0, 0, 0};
  auto y_of = [&](double c) {
    const double t = std::clamp((c - 0.8) / 0.2, 0.0, 1.0);
    return static_cast<int>(std::lround((1.0 - t) * (kPanel - 1)));
  };
  auto band_y = [&](double share) {
    return kPanel + kGap + static_cast<int>(std::lround((1.0 - std::clamp(share, 0.0, 1.0)) * (kBand - 1)));
  };
  for (double g = 0.8; g <= 1.0001; g += 0.05)
    for (int x = 0; x < kWidth; ++x) img.at(x, y_of(g)) = grid;
  for (int x = 0; x < kWidth; ++x) img.at(x, y_of(pair_threshold)) = threshold;
  const std::size_t n = rows.size();
  std::vector<int> scans_in(kWidth, 0), drops_in(kWidth, 0);
  std::vector<double> running(kWidth, -1.0);  // drop ratio over the last kRunning scans, at the column's last scan
  std::size_t recent_drops = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const int x = static_cast<int>(static_cast<double>(i) * kWidth / static_cast<double>(std::max<std::size_t>(n, 1)));
    const ScanFilter::Decision& d = rows[i].decision;
    const int y = y_of(d.min_correlation);
    for (int dy = -1; dy <= 1; ++dy)
      if (y + dy >= 0 && y + dy < kPanel) img.at(x, y + dy) = d.keep ? kept : dropped;
    ++scans_in[x];
    if (!d.keep) ++drops_in[x], ++recent_drops;
    if (i >= kRunning && !rows[i - kRunning].decision.keep) --recent_drops;
    running[x] = static_cast<double>(recent_drops) / static_cast<double>(std::min(i + 1, kRunning));
  }
  for (int x = 0; x < kWidth; ++x) {
    if (scans_in[x] == 0) continue;
    const double share = static_cast<double>(drops_in[x]) / scans_in[x];
    auto mix = [share](int white, int red) { return static_cast<std::uint8_t>(std::lround(white + share * (red - white))); };
    const Rgb shade{mix(255, dropped.r), mix(255, dropped.g), mix(255, dropped.b)};
    for (int yy = kPanel + kGap; yy < img.height; ++yy) img.at(x, yy) = shade;
    img.at(x, band_y(0.5)) = grid;
  }
  int last_y = -1;
  for (int x = 0; x < kWidth; ++x) {
    if (running[x] < 0.0) continue;
    const int y = band_y(running[x]);
    for (int yy = last_y < 0 ? y : std::min(y, last_y); yy <= (last_y < 0 ? y : std::max(y, last_y)); ++yy)
      img.at(x, yy) = ink;
    last_y = y;
  }
  write_png(path, img);
}

void run_filter(FilterArgs& a) {
  a.config.statistic = a.statistic == "mean" ? HistogramStatistic::mean : HistogramStatistic::median;
  a.config.binning = a.binning == "distance" ? HistogramBinning::distance : HistogramBinning::sector;
  a.config.common_threshold = a.common_threshold;
  ScanFilter filter(a.config);  // validates before the (slow) read

  LogReadOptions read;
  read.scan_topic = a.scan_topic;
  read.odom_topic = a.odom_topic;
  const SensorLog log = read_log(a.log, read);
  for (const auto& w : log.warnings) fmt::print(stderr, "warning: {}\n", w);
  if (log.scans.empty()) throw InputError(a.log + ": no laser scans");

  std::vector<DecisionRow> rows;
  rows.reserve(log.scans.size());
  std::vector<LaserScan> kept;
  std::map<std::string, std::size_t> reasons;
  std::chrono::steady_clock::duration filter_time{};
  for (const LaserScan& scan : log.scans) {
    const auto start = std::chrono::steady_clock::now();
    ScanFilter::Decision d;
    if (a.no_odometry) {
      LaserScan blind = scan;
      blind.odometry.reset();
      d = filter.decide(blind);
    } else {
      d = filter.decide(scan);
    }
    filter_time += std::chrono::steady_clock::now() - start;
    rows.push_back({scan.timestamp, d});
    ++reasons[d.reason];
    if (d.keep) kept.push_back(scan);
  }
  const double filter_seconds = std::chrono::duration<double>(filter_time).count();

  const std::size_t read_count = log.scans.size();
  const double drop_ratio = static_cast<double>(filter.dropped()) / static_cast<double>(read_count);
  const ScanFilterConfig& c = filter.config();
  const std::string columns = c.columns == 0 ? fmt::format("auto ({} for {} beams)",
                                                           default_column_count(log.scans.front().ranges.size()),
                                                           log.scans.front().ranges.size())
                                             : std::to_string(c.columns);
  const std::string common = c.common_threshold ? fmt::format("{}", *c.common_threshold) : "P_pair^window";
  write_carmen(a.out, kept,
               fmt::format("dsswarm filter of {}: kept {} of {} scans\ncolumns {}, {}, {} binning, P_pair {}, "
                           "P_common {}",
                           a.log, kept.size(), read_count, columns, a.statistic, a.binning, c.pair_threshold, common));
  if (!a.decisions.empty()) write_decisions(a.decisions, rows);
  if (!a.plot.empty()) write_plot(a.plot, rows, c.pair_threshold);

  fmt::print("scan filter: {} -> {}\n", a.log, a.out);
  fmt::print("  histogram: {} columns, {} of each {}, P_pair {}, P_common {}{}\n", columns,
             c.binning == HistogramBinning::sector ? a.statistic : "count",
             c.binning == HistogramBinning::sector ? "sector" : "range interval", c.pair_threshold, common,
             a.no_odometry ? ", odometry ignored" : "");
  fmt::print("  scans read: {}, kept: {}, dropped: {}, drop ratio: {:.4f}\n", read_count, filter.kept(),
             filter.dropped(), drop_ratio);
  std::string why;
  for (const auto& [reason, count] : reasons) why += fmt::format("{}{} {}", why.empty() ? "" : ", ", reason, count);
  fmt::print("  decisions: {}\n", why);
  fmt::print("  filter_seconds: {:.4f} ({:.1f} us per scan)\n", filter_seconds,
             1e6 * filter_seconds / static_cast<double>(read_count));
  const nlohmann::json summary = {{"scans_read", read_count},           {"scans_kept", filter.kept()},
                                  {"scans_dropped", filter.dropped()}, {"drop_ratio", drop_ratio},
                                  {"filter_seconds", filter_seconds}};
  fmt::print("{}\n", summary.dump());
  std::fflush(stdout);
}

}  // namespace

void add_filter_command(CLI::App& app) {
  auto args = std::make_shared<FilterArgs>();
  ScanFilterConfig& c = args->config;
  CLI::App* cmd = app.add_subcommand("filter", "Drop redundant laser scans (histogram correlation filter)");
  cmd->add_option("log", args->log, "Log (CARMEN, ROS1 bag or ROS 2 bag)")->required()->check(CLI::ExistingPath);
  cmd->add_option("--out", args->out, "Filtered log to write (CARMEN, the kept scans)")->required();
  cmd->add_option("--decisions", args->decisions,
                  "CSV with one row per scan: index,timestamp,kept,min_correlation,product,window,reason");
  cmd->add_option("--plot", args->plot,
                  "PNG over time: min correlation with the window (0.8 bottom to 1.0 top, P_pair in blue, "
                  "dropped scans red) and a red band where scans were dropped");
  cmd->add_option("--scan-topic", args->scan_topic, "ROS bag: sensor_msgs/LaserScan topic")->capture_default_str();
  cmd->add_option("--odom-topic", args->odom_topic, "ROS bag: nav_msgs/Odometry topic")->capture_default_str();
  cmd->add_flag("--no-odometry", args->no_odometry, "Ignore odometry: fixed window, no motion valve");
  cmd->add_option("--columns", c.columns, "Histogram columns B (0 = clamp(round(15 n/1000), 6, 30) for n beams)")
      ->capture_default_str();
  cmd->add_option("--statistic", args->statistic, "Column value for sector binning")
      ->check(CLI::IsMember({"median", "mean"}))
      ->capture_default_str();
  cmd->add_option("--binning", args->binning, "sector: by beam index; distance: point counts per range interval")
      ->check(CLI::IsMember({"sector", "distance"}))
      ->capture_default_str();
  cmd->add_option("--pair", c.pair_threshold, "P_pair, pairwise correlation threshold [0.95, 0.99]")
      ->capture_default_str();
  cmd->add_option("--common", args->common_threshold, "P_common, product threshold (default P_pair^window)");
  cmd->add_option("--window", c.fixed_window, "Window size without odometry")->capture_default_str();
  cmd->add_option("--min-window", c.min_window, "Smallest window (fast robot)")->capture_default_str();
  cmd->add_option("--max-window", c.max_window, "Largest window (standing robot)")->capture_default_str();
  cmd->add_option("--speed-samples", c.speed_samples, "Scans in the running mean of travel per scan")
      ->capture_default_str();
  cmd->add_option("--max-drops", c.max_consecutive_drops, "Most scans dropped in a row")->capture_default_str();
  cmd->add_option("--max-translation", c.max_translation,
                  "Keep once odometry moved this far since the last kept scan (m)")
      ->capture_default_str();
  cmd->add_option("--max-rotation", c.max_rotation,
                  "Keep once odometry turned this much since the last kept scan (rad)")
      ->capture_default_str();
  cmd->add_option("--doubt-ratio", c.doubt_ratio,
                  "Keep when the view ahead moved against odometry's forward travel by more than this share "
                  "of it (inf: off)")
      ->capture_default_str();
  cmd->callback([args] { run_filter(*args); });
}

}  // namespace dsswarm
