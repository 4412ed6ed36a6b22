#include "eval/relations.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <string_view>

#include <fmt/format.h>

#include "common/errors.hpp"
#include "eval/trajectory_lookup.hpp"
#include "io/trajectory/text_fields.hpp"

namespace dsswarm {

namespace {

constexpr std::array<std::string_view, 8> kFieldNames = {"t1", "t2", "x", "y", "z", "roll", "pitch", "yaw"};

Relation parse_relation_line(std::string_view line, const std::string& where) {
  auto fields = split_fields(line);
  if (!fields.empty() && fields.front() == "FLOAT") fields.erase(fields.begin());
  if (fields.size() != kFieldNames.size()) {
    throw InputError(fmt::format("{}: expected 8 numbers (t1 t2 x y z roll pitch yaw), found {}", where,
                                 fields.size()));
  }
  std::array<double, 8> v{};
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = parse_finite_field(fields[i], where, kFieldNames[i]);
  return {v[0], v[1], Pose2(v[2], v[3], v[7])};
}

struct MeanStd {
  double mean = 0.0;
  double stddev = 0.0;
};

// Two-pass population mean and standard deviation; `values` is non-empty.
MeanStd mean_and_std(const std::vector<double>& values) {
  double sum = 0.0;
  for (const double v : values) sum += v;
  const double mean = sum / static_cast<double>(values.size());
  double squares = 0.0;
  for (const double v : values) squares += (v - mean) * (v - mean);
  return {mean, std::sqrt(squares / static_cast<double>(values.size()))};
}

}  // namespace

std::vector<Relation> read_relations(std::istream& in, const std::string& source_name) {
  std::vector<Relation> relations;
  for_each_data_line(in, source_name, [&](std::string_view line, const std::string& where) {
    relations.push_back(parse_relation_line(line, where));
  });
  if (relations.empty()) throw InputError(fmt::format("{}: no relations found", source_name));
  return relations;
}

std::vector<Relation> read_relations(const std::filesystem::path& path) {
  std::ifstream in = open_text_input(path, "relations");
  return read_relations(in, path.string());
}

RelationMetrics evaluate_relations(const Trajectory& estimate, const std::vector<Relation>& relations,
                                   double max_time_diff) {
  require_valid_max_time_diff(max_time_diff);
  const TimestampIndex index(estimate, "estimated");
  RelationMetrics m;
  m.trans_errors.reserve(relations.size());
  m.rot_errors_deg.reserve(relations.size());
  for (const Relation& r : relations) {
    const auto i1 = index.nearest(r.t1, max_time_diff);
    const auto i2 = index.nearest(r.t2, max_time_diff);
    if (!i1 || !i2) {
      ++m.missing;
      continue;
    }
    const Pose2 estimated_motion = between(estimate[*i1].pose, estimate[*i2].pose);
    const Pose2 error = between(r.motion, estimated_motion);  // δ⁻¹ ⊕ δ̂
    m.trans_errors.push_back(std::hypot(error.x, error.y));
    m.rot_errors_deg.push_back(std::abs(error.theta) * 180.0 / std::numbers::pi);
  }
  m.used = m.trans_errors.size();
  if (m.used == 0) {
    if (relations.empty()) throw InputError("relation metric: no relations given");
    double first = relations.front().t1, last = relations.front().t1;
    for (const Relation& r : relations) {
      first = std::min({first, r.t1, r.t2});
      last = std::max({last, r.t1, r.t2});
    }
    const std::string span = index.empty() ? std::string("the trajectory is empty")
                                           : fmt::format("trajectory timestamps span [{:.6f}, {:.6f}]",
                                                         index.earliest(), index.latest());
    throw InputError(fmt::format(
        "relation metric: none of the {} relations has estimated poses within {} s of both t1 and t2 "
        "(relations span [{:.6f}, {:.6f}], {}); is this the trajectory of the right log, with its "
        "original timestamps?",
        relations.size(), max_time_diff, first, last, span));
  }
  const MeanStd trans = mean_and_std(m.trans_errors);
  const MeanStd rot = mean_and_std(m.rot_errors_deg);
  m.trans_mean = trans.mean;
  m.trans_std = trans.stddev;
  m.rot_mean_deg = rot.mean;
  m.rot_std_deg = rot.stddev;
  return m;
}

}  // namespace dsswarm
