#include "apps/filter_command.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <iterator>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "apps/filter_plot.hpp"
#include "common/errors.hpp"
#include "filter/scan_filter.hpp"
#include "io/atomic_file.hpp"
#include "io/logs/carmen_writer.hpp"
#include "io/logs/log_reader.hpp"
#include "io/maps/render.hpp"
#include "io/output_paths.hpp"

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
  bool tf_odometry = false;
  bool odom_topic_named = false;  // --odom-topic given: a topic the bag lacks is an error
  bool no_odometry = false;
  std::string statistic = "median";
  std::string binning = "sector";
  std::optional<double> common_threshold;
  ScanFilterConfig config;
};

std::string decisions_csv(const std::vector<DecisionRow>& rows) {
  std::string csv = "index,timestamp,kept,min_correlation,product,window,reason\n";
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const ScanFilter::Decision& d = rows[i].decision;
    fmt::format_to(std::back_inserter(csv), "{},{},{},{:.6f},{:.6f},{},{}\n", i, rows[i].timestamp, d.keep ? 1 : 0,
                   d.min_correlation, d.product, d.window, d.reason);
  }
  return csv;
}

void run_filter(FilterArgs& a) {
  check_output_file(a.out, "--out");  // before the (slow) read
  if (!a.decisions.empty()) check_output_file(a.decisions, "--decisions");
  if (!a.plot.empty()) check_output_file(a.plot, "--plot");
  a.config.statistic = a.statistic == "mean" ? HistogramStatistic::mean : HistogramStatistic::median;
  a.config.binning = a.binning == "distance" ? HistogramBinning::distance : HistogramBinning::sector;
  a.config.common_threshold = a.common_threshold;
  ScanFilter filter(a.config);  // validates before the read

  LogReadOptions read;
  read.scan_topic = a.scan_topic;
  read.odom_topic = a.odom_topic;
  read.use_tf_odometry = a.tf_odometry;
  read.odom_topic_named = a.odom_topic_named;
  const SensorLog log = read_log(a.log, read);
  for (const auto& w : log.warnings) spdlog::warn("{}", w);
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
  OutputFiles files;
  files.add(a.out, format_carmen(a.out, kept,
                                 fmt::format("dsswarm filter of {}: kept {} of {} scans\ncolumns {}, {}, {} binning, "
                                             "P_pair {}, P_common {}",
                                             a.log, kept.size(), read_count, columns, a.statistic, a.binning,
                                             c.pair_threshold, common)));
  if (!a.decisions.empty()) files.add(a.decisions, decisions_csv(rows));
  if (!a.plot.empty()) files.add(a.plot, encode_png(a.plot, filter_plot(rows, c.pair_threshold)));
  files.write_all();

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
  cmd->add_option("log", args->log, "Log file (CARMEN or ROS1 bag)")->required();
  cmd->add_option("--out", args->out, "Filtered log to write (CARMEN, the kept scans)")->required();
  cmd->add_option("--decisions", args->decisions,
                  "CSV with one row per scan: index,timestamp,kept,min_correlation,product,window,reason");
  cmd->add_option("--plot", args->plot,
                  "PNG over time: min correlation with the window (0.8 bottom to 1.0 top, P_pair in blue, "
                  "dropped scans red) and a red band where scans were dropped");
  cmd->add_option("--scan-topic", args->scan_topic, "ROS bag: sensor_msgs/LaserScan topic")->capture_default_str();
  const CLI::Option* odom_topic =
      cmd->add_option("--odom-topic", args->odom_topic, "ROS bag: nav_msgs/Odometry topic")->capture_default_str();
  cmd->add_flag("--tf-odometry", args->tf_odometry, "ROS bag: take odometry from /tf instead of the odometry topic");
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
  cmd->callback([args, odom_topic] {
    args->odom_topic_named = odom_topic->count() > 0;
    run_filter(*args);
  });
}

}  // namespace dsswarm
