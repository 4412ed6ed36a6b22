#include "config/config_json.hpp"

#include <cmath>
#include <cstdint>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <type_traits>
#include <array>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>

#include "common/errors.hpp"
#include "config/key_suggestion.hpp"

namespace dsswarm {

// Enumerations are written by name. (nlohmann's NLOHMANN_JSON_SERIALIZE_ENUM
// would read an unknown name as the first value, silently.)
namespace {
template <typename Enum>
using EnumNames = std::array<std::pair<Enum, const char*>, 2>;
constexpr EnumNames<HistogramStatistic> kStatistics{{{HistogramStatistic::median, "median"},
                                                     {HistogramStatistic::mean, "mean"}}};
constexpr EnumNames<HistogramBinning> kBinnings{{{HistogramBinning::sector, "sector"},
                                                 {HistogramBinning::distance, "distance"}}};

template <typename Enum>
std::string name_of(Enum e, const EnumNames<Enum>& names) {
  for (const auto& [value, name] : names)
    if (value == e) return name;
  return "?";
}

template <typename Enum>
Enum value_of(const nlohmann::json& j, const EnumNames<Enum>& names) {
  const std::string given = j.get<std::string>();  // not a string: a type error
  for (const auto& [value, name] : names)
    if (given == name) return value;
  throw std::invalid_argument(fmt::format("must be one of {}, {} (got \"{}\")", names[0].second, names[1].second, given));
}
}  // namespace

void to_json(nlohmann::json& j, HistogramStatistic s) { j = name_of(s, kStatistics); }
void from_json(const nlohmann::json& j, HistogramStatistic& s) { s = value_of(j, kStatistics); }
void to_json(nlohmann::json& j, HistogramBinning b) { j = name_of(b, kBinnings); }
void from_json(const nlohmann::json& j, HistogramBinning& b) { b = value_of(j, kBinnings); }

namespace {

using nlohmann::json;

// One table of fields drives both directions, so the two can never disagree.
struct Field {
  std::function<json(const SwarmConfig&)> get;
  std::function<void(const json&, SwarmConfig&)> set;
};

// A float is written as the shortest decimal that reads back as the same
// float (0.4, not its double widening 0.4000000059604645).
template <typename T>
json to_json_value(const T& v) {
  if constexpr (std::is_same_v<T, float>) return json(std::stod(fmt::format("{}", v)));
  return json(v);
}

// A whole-number field. nlohmann's get<int>() truncates 2.5 to 2, wraps
// 4294967298 to 2, reads true as 1, and converting 1e10 to int is undefined
// behaviour (found by fuzzing): only whole numbers in range are taken.
template <typename T>
T whole_number(const json& j) {
  const auto refuse = [&] {
    return std::invalid_argument(fmt::format("must be a whole number from {} to {} (got {})",
                                             std::numeric_limits<T>::min(), std::numeric_limits<T>::max(), j.dump()));
  };
  if (j.is_number_unsigned() || j.is_number_integer()) {
    const bool in_range = j.is_number_unsigned() ? std::in_range<T>(j.get<std::uint64_t>())
                                                 : std::in_range<T>(j.get<std::int64_t>());
    if (!in_range) throw refuse();
    return j.is_number_unsigned() ? static_cast<T>(j.get<std::uint64_t>()) : static_cast<T>(j.get<std::int64_t>());
  }
  if (j.is_number_float()) {
    const double v = j.get<double>();
    const double end = std::ldexp(1.0, std::numeric_limits<T>::digits);  // one past the largest T
    if (v != std::trunc(v) || v < static_cast<double>(std::numeric_limits<T>::min()) || v >= end) throw refuse();
    return static_cast<T>(v);
  }
  throw refuse();
}

template <typename T, typename Member>
Field field(Member member) {
  return {[member](const SwarmConfig& c) { return to_json_value<T>(std::invoke(member, c)); },
          [member](const json& j, SwarmConfig& c) {
            if constexpr (std::is_integral_v<T> && !std::is_same_v<T, bool>) {
              std::invoke(member, c) = whole_number<T>(j);
            } else {
              std::invoke(member, c) = j.get<T>();
            }
          }};
}

// A SLAM field lives in SwarmConfig::slam; a swarm field in SwarmConfig itself.
#define DSS_FIELD(T, path) field<T>([](auto& c) -> auto& { return c.slam.path; })
#define DSS_SWARM_FIELD(T, path) field<T>([](auto& c) -> auto& { return c.path; })

// The swarm sections; a single robot's configuration has only the others.
bool is_swarm_section(const std::string& section) { return section == "encounter" || section == "swarm"; }

const std::map<std::string, std::map<std::string, Field>>& fields() {
  static const std::map<std::string, std::map<std::string, Field>> table = {
      {"filter",
       {{"enabled", DSS_FIELD(bool, use_filter)},
        {"revise_dropped", DSS_FIELD(bool, revise_dropped)},
        {"columns", DSS_FIELD(int, filter.columns)},
        {"statistic", DSS_FIELD(HistogramStatistic, filter.statistic)},
        {"binning", DSS_FIELD(HistogramBinning, filter.binning)},
        {"pair_threshold", DSS_FIELD(double, filter.pair_threshold)},
        {"window_constant", DSS_FIELD(double, filter.window_constant)},
        {"min_window", DSS_FIELD(int, filter.min_window)},
        {"max_window", DSS_FIELD(int, filter.max_window)},
        {"fixed_window", DSS_FIELD(int, filter.fixed_window)},
        {"max_consecutive_drops", DSS_FIELD(int, filter.max_consecutive_drops)},
        {"max_translation", DSS_FIELD(double, filter.max_translation)},
        {"max_rotation", DSS_FIELD(double, filter.max_rotation)},
        {"doubt_ratio", DSS_FIELD(double, filter.doubt_ratio)},
        {"doubt_min_travel", DSS_FIELD(double, filter.doubt_min_travel)},
        {"doubt_cone", DSS_FIELD(double, filter.doubt_cone)}}},
      {"map",
       {{"resolution", DSS_FIELD(double, map.resolution)},
        {"levels", DSS_FIELD(int, map.levels)},
        {"free_space_on_coarse_levels", DSS_FIELD(bool, map.free_space_on_coarse_levels)},
        {"free_margin_cells", DSS_FIELD(double, map.free_margin_cells)},
        {"splat_fine_hits", DSS_FIELD(bool, map.splat_fine_hits)},
        {"surface_gap", DSS_FIELD(double, map.surface_gap)},
        {"surface_mass_factor", DSS_FIELD(float, map.surface_mass_factor)},
        {"surface_max_cos", DSS_FIELD(double, map.surface_max_cos)}}},
      {"evidence",
       {{"hit_occupied", DSS_FIELD(float, map.evidence.hit_occupied)},
        {"pass_free", DSS_FIELD(float, map.evidence.pass_free)},
        {"min_unknown", DSS_FIELD(float, map.evidence.min_unknown)}}},
      {"matcher",
       {{"evaluations", DSS_FIELD(int, matcher.evaluations)},
        {"sigma_xy", DSS_FIELD(double, matcher.sigma_xy)},
        {"sigma_theta", DSS_FIELD(double, matcher.sigma_theta)},
        {"shrink_on_success", DSS_FIELD(double, matcher.shrink_on_success)},
        {"patience", DSS_FIELD(int, matcher.patience)},
        {"min_sigma_xy", DSS_FIELD(double, matcher.min_sigma_xy)},
        {"min_sigma_theta", DSS_FIELD(double, matcher.min_sigma_theta)},
        {"converged_fraction", DSS_FIELD(double, matcher.converged_fraction)},
        {"polish_evaluations", DSS_FIELD(int, matcher.polish_evaluations)},
        {"polish_heat_evaluations", DSS_FIELD(int, matcher.polish_heat_evaluations)},
        {"fine_search_stride", DSS_FIELD(int, matcher.fine_search_stride)},
        {"fine_merge_cells", DSS_FIELD(double, matcher.fine_merge_cells)},
        {"coarse_stride", DSS_FIELD(int, matcher.coarse_stride)},
        {"coarse_merge_cells", DSS_FIELD(double, matcher.coarse_merge_cells)},
        {"polish_step_theta", DSS_FIELD(double, matcher.polish_step_theta)},
        {"unknown_value", DSS_FIELD(float, matcher.unknown_value)},
        {"prior_weight", DSS_FIELD(double, matcher.prior_weight)},
        {"prior_sigma_xy", DSS_FIELD(double, matcher.prior_sigma_xy)},
        {"prior_sigma_theta", DSS_FIELD(double, matcher.prior_sigma_theta)}}},
      {"points",
       {{"forward_gain", DSS_FIELD(double, points.forward_gain)},
        {"forward_power", DSS_FIELD(double, points.forward_power)},
        {"min_range", DSS_FIELD(double, points.min_range)},
        {"max_range", DSS_FIELD(double, points.max_range)}}},
      {"slam",
       {{"use_odometry", DSS_FIELD(bool, use_odometry)},
        {"seed", DSS_FIELD(std::uint64_t, seed)},
        {"min_points", DSS_FIELD(int, min_points)},
        {"odometry_doubt_xy", DSS_FIELD(double, motion.odometry_doubt_xy)},
        {"odometry_doubt_theta", DSS_FIELD(double, motion.odometry_doubt_theta)},
        {"verify_min_known", DSS_FIELD(double, verify.min_known)},
        {"verify_min_inliers", DSS_FIELD(double, verify.min_inliers)},
        {"verify_relative", DSS_FIELD(double, verify.relative)},
        {"verify_max_consecutive", DSS_FIELD(int, verify.max_consecutive)},
        {"verify_average_weight", DSS_FIELD(double, verify.average_weight)},
        {"recovery_evaluations_factor", DSS_FIELD(int, recovery.evaluations_factor)},
        {"recovery_sigma_xy_factor", DSS_FIELD(double, recovery.sigma_xy_factor)},
        {"recovery_sigma_theta_factor", DSS_FIELD(double, recovery.sigma_theta_factor)},
        {"recovery_patience_factor", DSS_FIELD(int, recovery.patience_factor)},
        {"degeneracy_min_ratio", DSS_FIELD(double, degeneracy.min_ratio)},
        {"degeneracy_normal_radius", DSS_FIELD(double, degeneracy.normal_radius)},
        {"degeneracy_normal_neighbors", DSS_FIELD(int, degeneracy.normal_neighbors)},
        {"degeneracy_min_patch", DSS_FIELD(int, degeneracy.min_patch)},
        {"degeneracy_max_patch_spread", DSS_FIELD(double, degeneracy.max_patch_spread)},
        {"degeneracy_min_normals", DSS_FIELD(int, degeneracy.min_normals)},
        {"stall_window", DSS_FIELD(double, stall.window)},
        {"stall_min_progress", DSS_FIELD(double, stall.min_progress)},
        {"stall_min_step", DSS_FIELD(double, stall.min_step)},
        {"stall_young_travel", DSS_FIELD(double, stall.young_travel)},
        {"stall_catch_up", DSS_FIELD(bool, stall.catch_up)},
        {"jump_factor", DSS_FIELD(double, jump.factor)},
        {"jump_percentile", DSS_FIELD(double, jump.percentile)},
        {"jump_min_distance", DSS_FIELD(double, jump.min_distance)},
        {"jump_min_gain", DSS_FIELD(double, jump.min_gain)},
        {"jump_history", DSS_FIELD(int, jump.history)},
        {"jump_min_history", DSS_FIELD(int, jump.min_history)},
        {"jump_confirm", DSS_FIELD(int, jump.confirm)},
        {"align_walls", DSS_FIELD(bool, align.enabled)},
        {"align_min_consistency", DSS_FIELD(double, align.min_consistency)},
        {"align_inlier_angle", DSS_FIELD(double, align.inlier_angle)},
        {"align_min_normals", DSS_FIELD(int, align.min_normals)},
        {"pause_after_still_scans", DSS_FIELD(int, pause_after_still_scans)},
        {"insert_min_travel", DSS_FIELD(double, insert.min_travel)},
        {"insert_min_rotation", DSS_FIELD(double, insert.min_rotation)}}},
      {"submaps",
       {{"max_scans", DSS_FIELD(int, submaps.max_scans)},
        {"max_travel", DSS_FIELD(double, submaps.max_travel)},
        {"keep_previous", DSS_FIELD(double, submaps.keep_previous)}}},
      {"loop_closure",
       {{"enabled", DSS_FIELD(bool, loop_closure.enabled)},
        {"node_spacing", DSS_FIELD(double, loop_closure.node_spacing)},
        {"node_rotation", DSS_FIELD(double, loop_closure.node_rotation)},
        {"overlap_nodes", DSS_FIELD(int, loop_closure.overlap_nodes)},
        {"search_spacing", DSS_FIELD(double, loop_closure.search_spacing)},
        {"max_distance", DSS_FIELD(double, loop_closure.max_distance)},
        {"max_submaps", DSS_FIELD(int, loop_closure.max_submaps)},
        {"window_xy", DSS_FIELD(double, loop_closure.window_xy)},
        {"window_xy_per_m", DSS_FIELD(double, loop_closure.window_xy_per_m)},
        {"max_window_xy", DSS_FIELD(double, loop_closure.max_window_xy)},
        {"window_theta", DSS_FIELD(double, loop_closure.window_theta)},
        {"window_theta_per_m", DSS_FIELD(double, loop_closure.window_theta_per_m)},
        {"max_window_theta", DSS_FIELD(double, loop_closure.max_window_theta)},
        {"points", DSS_FIELD(int, loop_closure.search.points)},
        {"max_range", DSS_FIELD(double, loop_closure.search.max_range)},
        {"max_depth", DSS_FIELD(int, loop_closure.search.max_depth)},
        {"min_score", DSS_FIELD(double, loop_closure.search.min_score)},
        {"refine_evaluations", DSS_FIELD(int, loop_closure.search.refine.evaluations)},
        {"min_known", DSS_FIELD(double, loop_closure.search.min_known)},
        {"min_inliers", DSS_FIELD(double, loop_closure.search.min_inliers)},
        {"min_same_side", DSS_FIELD(double, loop_closure.search.min_same_side)},
        {"max_runner_up", DSS_FIELD(double, loop_closure.search.max_runner_up)},
        {"runner_up_xy", DSS_FIELD(double, loop_closure.search.runner_up_xy)},
        {"runner_up_theta", DSS_FIELD(double, loop_closure.search.runner_up_theta)},
        {"min_prior_known", DSS_FIELD(double, loop_closure.search.min_prior_known)},
        {"reclose_travel", DSS_FIELD(double, loop_closure.reclose_travel)},
        {"consistency_travel", DSS_FIELD(double, loop_closure.consistency_travel)},
        {"agree_xy", DSS_FIELD(double, loop_closure.agree_xy)},
        {"agree_theta", DSS_FIELD(double, loop_closure.agree_theta)},
        {"pending_rounds", DSS_FIELD(int, loop_closure.pending_rounds)},
        {"max_residual_xy", DSS_FIELD(double, loop_closure.max_residual_xy)},
        {"max_residual_theta", DSS_FIELD(double, loop_closure.max_residual_theta)},
        {"round_nodes", DSS_FIELD(int, loop_closure.round_nodes)},
        {"rounds_in_flight", DSS_FIELD(int, loop_closure.rounds_in_flight)},
        {"foreign_max_pieces", DSS_FIELD(int, loop_closure.foreign_max_pieces)},
        {"foreign_backlog", DSS_FIELD(int, loop_closure.foreign_backlog)}}},
      {"graph",
       {{"local_sigma_xy", DSS_FIELD(double, loop_closure.graph.local_sigma_xy)},
        {"local_sigma_theta", DSS_FIELD(double, loop_closure.graph.local_sigma_theta)},
        {"loop_sigma_xy", DSS_FIELD(double, loop_closure.graph.loop_sigma_xy)},
        {"loop_sigma_theta", DSS_FIELD(double, loop_closure.graph.loop_sigma_theta)},
        {"foreign_sigma_xy", DSS_FIELD(double, loop_closure.graph.foreign_sigma_xy)},
        {"foreign_sigma_theta", DSS_FIELD(double, loop_closure.graph.foreign_sigma_theta)},
        {"loop_huber", DSS_FIELD(double, loop_closure.graph.loop_huber)},
        {"foreign_moves_own", DSS_FIELD(bool, loop_closure.graph.foreign_moves_own)},
        {"peer_weight", DSS_FIELD(double, loop_closure.graph.peer_weight)},
        {"max_iterations", DSS_FIELD(int, loop_closure.graph.max_iterations)}}},
      {"encounter",
       {{"search_radius", DSS_SWARM_FIELD(double, encounter.locate.search_radius)},
        {"coarse_step_xy", DSS_SWARM_FIELD(double, encounter.locate.coarse_step_xy)},
        {"coarse_step_theta", DSS_SWARM_FIELD(double, encounter.locate.coarse_step_theta)},
        {"coarse_points", DSS_SWARM_FIELD(int, encounter.locate.coarse_points)},
        {"candidates", DSS_SWARM_FIELD(int, encounter.locate.candidates)},
        {"surroundings_radius", DSS_SWARM_FIELD(double, encounter.locate.surroundings_radius)},
        {"surroundings_points", DSS_SWARM_FIELD(int, encounter.locate.surroundings_points)},
        {"merge_surroundings_radius", DSS_SWARM_FIELD(double, encounter.locate.merge_surroundings_radius)},
        {"merge_surroundings_points", DSS_SWARM_FIELD(int, encounter.locate.merge_surroundings_points)},
        {"polish_sigma_xy", DSS_SWARM_FIELD(double, encounter.locate.polish_sigma_xy)},
        {"polish_sigma_theta", DSS_SWARM_FIELD(double, encounter.locate.polish_sigma_theta)},
        {"place_in_recent_submaps", DSS_SWARM_FIELD(bool, encounter.locate.place_in_recent_submaps)},
        {"mode_separation_xy", DSS_SWARM_FIELD(double, encounter.locate.mode_separation_xy)},
        {"mode_separation_theta", DSS_SWARM_FIELD(double, encounter.locate.mode_separation_theta)},
        {"possible_same_side", DSS_SWARM_FIELD(double, encounter.locate.possible_same_side)},
        {"refine_evaluations", DSS_SWARM_FIELD(int, encounter.locate.refine.evaluations)},
        {"min_known_fraction", DSS_SWARM_FIELD(double, encounter.min_known_fraction)},
        {"min_inlier_ratio", DSS_SWARM_FIELD(double, encounter.min_inlier_ratio)},
        {"min_same_side", DSS_SWARM_FIELD(double, encounter.min_same_side)},
        {"max_runner_up_ratio", DSS_SWARM_FIELD(double, encounter.max_runner_up_ratio)},
        {"agree_xy", DSS_SWARM_FIELD(double, encounter.agree_xy)},
        {"agree_theta", DSS_SWARM_FIELD(double, encounter.agree_theta)},
        {"reject_bent_maps", DSS_SWARM_FIELD(bool, encounter.reject_bent_maps)}}},
      {"swarm",
       {{"remerge_interval", DSS_SWARM_FIELD(double, remerge_interval)},
        {"merge_delay", DSS_SWARM_FIELD(double, merge_delay)},
        {"confirm", DSS_SWARM_FIELD(bool, confirm)},
        {"confirm_xy", DSS_SWARM_FIELD(double, confirm_xy)},
        {"confirm_theta", DSS_SWARM_FIELD(double, confirm_theta)},
        {"confirm_by_directions", DSS_SWARM_FIELD(bool, confirm_by_directions)},
        {"repeat_xy", DSS_SWARM_FIELD(double, repeat_xy)},
        {"repeat_theta", DSS_SWARM_FIELD(double, repeat_theta)},
        {"repeat_retries", DSS_SWARM_FIELD(int, repeat_retries)},
        {"exchange_timeout", DSS_SWARM_FIELD(double, exchange_timeout)},
        {"offer_timeout", DSS_SWARM_FIELD(double, offer_timeout)},
        {"chunk_bytes", DSS_SWARM_FIELD(std::size_t, chunk_bytes)},
        {"max_open_encounters", DSS_SWARM_FIELD(std::size_t, max_open_encounters)},
        {"max_pending_confirmations", DSS_SWARM_FIELD(std::size_t, max_pending_confirmations)},
        {"remembered_encounters", DSS_SWARM_FIELD(std::size_t, remembered_encounters)},
        {"max_transfer_bytes", DSS_SWARM_FIELD(std::size_t, max_transfer_bytes)},
        {"moves_interval", DSS_SWARM_FIELD(double, moves_interval)},
        {"max_followed_encounters", DSS_SWARM_FIELD(std::size_t, max_followed_encounters)},
        {"max_moved_closures", DSS_SWARM_FIELD(std::size_t, max_moved_closures)},
        {"final_exchanges", DSS_SWARM_FIELD(int, final_exchanges)}}},
  };
  return table;
}

#undef DSS_FIELD
#undef DSS_SWARM_FIELD

// " (did you mean …?)" for an unknown section (`key` empty) or key, or "".
std::string did_you_mean(std::string_view section, std::string_view key) {
  static const KnownKeys known = [] {
    KnownKeys k;
    for (const auto& [name, members] : fields())
      for (const auto& member : members) k[name].push_back(member.first);
    return k;
  }();
  const auto guess = suggest_key(known, section, key);
  if (!guess) return "";
  if (!key.empty() && guess->find('.') == std::string::npos)
    return " (did you mean the section '" + *guess + "'? it stands at the top level)";
  return " (did you mean '" + *guess + "'?)";
}

// `input` is a stream or a string; `source` names it in errors.
template <typename Input, typename Config>
void parse_and_apply(Input&& input, const std::string& source, Config& config) {
  json j;
  try {
    j = json::parse(std::forward<Input>(input));
  } catch (const json::exception& e) {  // parse_error, and out_of_range for a number like 1e400
    throw ConfigError(source + ": not valid JSON (" + e.what() + ")");
  }
  apply_json(j, config, source);
  try {
    config.validate();
  } catch (const ConfigError& e) {
    throw ConfigError(source + ": " + e.what());
  }
}

template <typename Config>
void load(const std::filesystem::path& path, Config& config) {
  std::ifstream in(path);
  if (!in) throw ConfigError("cannot open config file " + path.string());
  parse_and_apply(in, path.string(), config);
}

}  // namespace

json to_json(const SwarmConfig& config) {
  json j = json::object();
  for (const auto& [section, members] : fields())
    for (const auto& [name, f] : members) j[section][name] = f.get(config);
  return j;
}

json to_json(const SlamConfig& config) {
  SwarmConfig swarm;
  swarm.slam = config;
  json j = to_json(swarm);
  for (auto it = j.begin(); it != j.end();) it = is_swarm_section(it.key()) ? j.erase(it) : std::next(it);
  return j;
}

void apply_json(const json& j, SwarmConfig& config, const std::string& source) {
  if (!j.is_object()) throw ConfigError(source + ": expected a JSON object at the top level");
  for (const auto& [section, body] : j.items()) {
    const auto s = fields().find(section);
    if (s == fields().end())
      throw ConfigError(source + ": unknown section '" + section + "'" + did_you_mean(section, ""));
    if (!body.is_object()) throw ConfigError(source + ": '" + section + "' must be an object");
    for (const auto& [name, value] : body.items()) {
      const auto f = s->second.find(name);
      if (f == s->second.end())
        throw ConfigError(source + ": unknown key '" + section + "." + name + "'" + did_you_mean(section, name));
      try {
        f->second.set(value, config);
      } catch (const json::exception&) {
        throw ConfigError(source + ": '" + section + "." + name + "' has the wrong type (" + value.dump() + ")");
      } catch (const std::invalid_argument& e) {
        throw ConfigError(source + ": '" + section + "." + name + "' " + e.what());
      }
    }
  }
}

void apply_json(const json& j, SlamConfig& config, const std::string& source) {
  SwarmConfig swarm;
  swarm.slam = config;
  apply_json(j, swarm, source);
  config = swarm.slam;
}

void load_config(const std::filesystem::path& path, SwarmConfig& config) { load(path, config); }

void load_slam_config(const std::filesystem::path& path, SlamConfig& config) { load(path, config); }

void parse_config(std::string_view text, const std::string& source, SwarmConfig& config) {
  parse_and_apply(text, source, config);
}

}  // namespace dsswarm
