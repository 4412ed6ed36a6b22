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
#include "apps/log_input.hpp"
#include "common/errors.hpp"
#include "config/config_json.hpp"
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
  std::string config_file;  // JSON, its `filter` section (as `dsswarm config` prints it)
  // The filter flags, each set only when given: they go on top of the file.
  std::optional<int> columns, fixed_window, min_window, max_window, speed_samples, max_drops;
  std::optional<std::string> statistic, binning;
  std::optional<double> pair, common, max_translation, max_rotation, doubt_ratio;
};

// Defaults, then the config file's filter section, then the flags given.
ScanFilterConfig resolve(const FilterArgs& a) {
  SlamConfig slam;
  if (!a.config_file.empty()) load_slam_config(a.config_file, slam);
  ScanFilterConfig c = slam.filter;
  const auto set = [](auto& field, const auto& flag) {
    if (flag) field = *flag;
  };
  set(c.columns, a.columns);
  set(c.fixed_window, a.fixed_window);
  set(c.min_window, a.min_window);
  set(c.max_window, a.max_window);
  set(c.speed_samples, a.speed_samples);
  set(c.max_consecutive_drops, a.max_drops);
  set(c.pair_threshold, a.pair);
  set(c.max_translation, a.max_translation);
  set(c.max_rotation, a.max_rotation);
  set(c.doubt_ratio, a.doubt_ratio);
  if (a.common) c.common_threshold = a.common;
  if (a.statistic) c.statistic = *a.statistic == "mean" ? HistogramStatistic::mean : HistogramStatistic::median;
  if (a.binning) c.binning = *a.binning == "distance" ? HistogramBinning::distance : HistogramBinning::sector;
  return c;
}

const char* name_of(HistogramStatistic s) { return s == HistogramStatistic::mean ? "mean" : "median"; }
const char* name_of(HistogramBinning b) { return b == HistogramBinning::distance ? "distance" : "sector"; }

// A filter flag whose help shows the built-in default (a --config file may change it).
template <class T, class Shown>
CLI::Option* add_setting(CLI::App* cmd, const std::string& name, std::optional<T>& flag, const Shown& shown,
                         const std::string& help) {
  return cmd->add_option(name, flag, help)->default_str(fmt::format("{}", shown));
}

std::string decisions_csv(const std::vector<DecisionRow>& rows) {
  std::string csv = "index,timestamp,kept,min_correlation,product,window,reason\n";
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const ScanFilter::Decision& d = rows[i].decision;
    fmt::format_to(std::back_inserter(csv), "{},{},{},{:.6f},{:.6f},{},{}\n", i, rows[i].timestamp, d.keep ? 1 : 0,
                   d.min_correlation, d.product, d.window, d.reason);
  }
  return csv;
}

// Every scan of `log` through `filter`, timed (the filter alone).
struct Filtered {
  std::vector<DecisionRow> rows;
  std::vector<LaserScan> kept;
  std::map<std::string, std::size_t> reasons;
  double seconds = 0.0;
};

Filtered filter_scans(ScanFilter& filter, const SensorLog& log, bool no_odometry) {
  Filtered f;
  f.rows.reserve(log.scans.size());
  std::chrono::steady_clock::duration filter_time{};
  for (const LaserScan& scan : log.scans) {
    const auto start = std::chrono::steady_clock::now();
    ScanFilter::Decision d;
    if (no_odometry) {
      LaserScan blind = scan;
      blind.odometry.reset();
      d = filter.decide(blind);
    } else {
      d = filter.decide(scan);
    }
    filter_time += std::chrono::steady_clock::now() - start;
    f.rows.push_back({scan.timestamp, d});
    ++f.reasons[d.reason];
    if (d.keep) f.kept.push_back(scan);
  }
  f.seconds = std::chrono::duration<double>(filter_time).count();
  return f;
}

void run_filter(const FilterArgs& a) {
  check_output_file(a.out, "--out");  // before the (slow) read
  if (!a.decisions.empty()) check_output_file(a.decisions, "--decisions");
  if (!a.plot.empty()) check_output_file(a.plot, "--plot");
  ScanFilter filter(resolve(a));  // validates before the read

  LogReadOptions read;
  read.scan_topic = a.scan_topic;
  read.odom_topic = a.odom_topic;
  read.use_tf_odometry = a.tf_odometry;
  read.odom_topic_named = a.odom_topic_named;
  const SensorLog log = read_input_log(a.log, read);

  const Filtered f = filter_scans(filter, log, a.no_odometry);
  const std::vector<DecisionRow>& rows = f.rows;
  const std::vector<LaserScan>& kept = f.kept;
  const double filter_seconds = f.seconds;

  const std::size_t read_count = log.scans.size();
  const double drop_ratio = static_cast<double>(filter.dropped()) / static_cast<double>(read_count);
  const ScanFilterConfig& c = filter.config();
  const std::string columns = c.columns == 0 ? fmt::format("auto ({} for {} beams)",
                                                           default_column_count(log.scans.front().ranges.size()),
                                                           log.scans.front().ranges.size())
                                             : std::to_string(c.columns);
  const std::string common = c.common_threshold ? fmt::format("{}", *c.common_threshold) : "P_pair^window";
  OutputFiles files;
  const std::string header =
      fmt::format("dsswarm filter of {}: kept {} of {} scans\ncolumns {}, {}, {} binning, P_pair {}, P_common {}",
                  a.log, kept.size(), read_count, columns, name_of(c.statistic), name_of(c.binning), c.pair_threshold,
                  common);
  files.add(a.out, format_carmen(a.out, kept, header));
  if (!a.decisions.empty()) files.add(a.decisions, decisions_csv(rows));
  if (!a.plot.empty()) files.add(a.plot, encode_png(a.plot, filter_plot(rows, c.pair_threshold)));
  files.write_all();

  fmt::print("scan filter: {} -> {}\n", a.log, a.out);
  fmt::print("  histogram: {} columns, {} of each {}, P_pair {}, P_common {}{}\n", columns,
             c.binning == HistogramBinning::sector ? name_of(c.statistic) : "count",
             c.binning == HistogramBinning::sector ? "sector" : "range interval", c.pair_threshold, common,
             a.no_odometry ? ", odometry ignored" : "");
  fmt::print("  scans read: {}, kept: {}, dropped: {}, drop ratio: {:.4f}\n", read_count, filter.kept(),
             filter.dropped(), drop_ratio);
  std::string why;
  for (const auto& [reason, count] : f.reasons) why += fmt::format("{}{} {}", why.empty() ? "" : ", ", reason, count);
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
  CLI::App* cmd = app.add_subcommand("filter", "Drop redundant laser scans (histogram correlation filter)");
  cmd->add_option("log", args->log, "Log (CARMEN, ROS1 bag or ROS 2 bag)")->required();
  cmd->add_option("--out", args->out, "Filtered log to write (CARMEN, the kept scans)")->required();
  cmd->add_option("--decisions", args->decisions,
                  "CSV with one row per scan: index,timestamp,kept,min_correlation,product,window,reason");
  cmd->add_option("--plot", args->plot,
                  "PNG of the decisions over the scans: each scan's smallest correlation with the window "
                  "(kept grey, dropped red, P_pair blue) and the share of scans dropped");
  cmd->add_option("--scan-topic", args->scan_topic, "ROS bag: sensor_msgs/LaserScan topic")->capture_default_str();
  const CLI::Option* odom_topic =
      cmd->add_option("--odom-topic", args->odom_topic, "ROS bag: nav_msgs/Odometry topic")->capture_default_str();
  cmd->add_flag("--tf-odometry", args->tf_odometry, "ROS bag: take odometry from /tf instead of the odometry topic");
  cmd->add_flag("--no-odometry", args->no_odometry, "Ignore odometry: fixed window, no motion valve");
  cmd->add_option("--config", args->config_file,
                  "Configuration (JSON): its filter section, below the flags given (`dsswarm config` prints it)")
      ->check(CLI::ExistingFile);
  const ScanFilterConfig d;  // the defaults the help shows
  add_setting(cmd, "--columns", args->columns, d.columns,
              "Histogram columns B (0 = clamp(round(15 n/1000), 6, 30) for n beams)");
  add_setting(cmd, "--statistic", args->statistic, name_of(d.statistic), "Column value for sector binning")
      ->check(CLI::IsMember({"median", "mean"}));
  add_setting(cmd, "--binning", args->binning, name_of(d.binning),
              "sector: by beam index; distance: point counts per range interval")
      ->check(CLI::IsMember({"sector", "distance"}));
  add_setting(cmd, "--pair", args->pair, d.pair_threshold, "P_pair, pairwise correlation threshold [0.95, 0.99]");
  cmd->add_option("--common", args->common, "P_common, product threshold (default P_pair^window)");
  add_setting(cmd, "--window", args->fixed_window, d.fixed_window, "Window size without odometry");
  add_setting(cmd, "--min-window", args->min_window, d.min_window, "Smallest window (fast robot)");
  add_setting(cmd, "--max-window", args->max_window, d.max_window, "Largest window (standing robot)");
  add_setting(cmd, "--speed-samples", args->speed_samples, d.speed_samples,
              "Scans in the running mean of travel per scan");
  add_setting(cmd, "--max-drops", args->max_drops, d.max_consecutive_drops, "Most scans dropped in a row");
  add_setting(cmd, "--max-translation", args->max_translation, d.max_translation,
              "Keep once odometry moved this far since the last kept scan (m)");
  add_setting(cmd, "--max-rotation", args->max_rotation, d.max_rotation,
              "Keep once odometry turned this much since the last kept scan (rad)");
  add_setting(cmd, "--doubt-ratio", args->doubt_ratio, d.doubt_ratio,
              "Keep when the view ahead moved against odometry's forward travel by more than this share of it "
              "(inf: off)");
  cmd->callback([args, odom_topic] {
    args->odom_topic_named = odom_topic->count() > 0;
    run_filter(*args);
  });
}

}  // namespace dsswarm
