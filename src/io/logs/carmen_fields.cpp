#include "io/logs/carmen_fields.hpp"

#include <fmt/format.h>

#include <cmath>

#include "common/errors.hpp"

namespace dsswarm::carmen_detail {

std::string shown(std::string_view token) {
  constexpr std::size_t kMax = 40;
  return token.size() <= kMax ? std::string(token) : std::string(token.substr(0, kMax)) + "...";
}

void Where::fail(std::string_view message) const {
  throw InputError(fmt::format("{}:{}: {}: {}", file, line, record, message));
}

double number_field(const Where& where, std::string_view token, std::string_view field) {
  double value = 0.0;
  if (!parse_whole(token, value)) {
    where.fail(fmt::format("field '{}' is not a number: '{}'", field, shown(token)));
  }
  return value;
}

double finite_field(const Where& where, std::string_view token, std::string_view field) {
  const double value = number_field(where, token, field);
  if (!std::isfinite(value)) where.fail(fmt::format("field '{}' must be finite, got '{}'", field, shown(token)));
  return value;
}

std::size_t count_field(const Where& where, std::string_view token, std::string_view field) {
  unsigned long long value = 0;
  if (!parse_whole(token, value)) {
    where.fail(fmt::format("field '{}' must be a whole number >= 0, got '{}'", field, shown(token)));
  }
  return static_cast<std::size_t>(value);
}

void read_ranges(const Where& where, const Tokens& fields, std::size_t first, std::size_t n,
                 std::vector<float>& ranges) {
  ranges.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (!parse_whole(fields[first + i], ranges[i])) {
      where.fail(fmt::format("field 'range {} of {}' is not a number: '{}'", i + 1, n, shown(fields[first + i])));
    }
  }
}

Pose2 pose_fields(const Where& where, const Tokens& fields, std::size_t first,
                  const std::array<std::string_view, 3>& names) {
  return {finite_field(where, fields[first], names[0]), finite_field(where, fields[first + 1], names[1]),
          finite_field(where, fields[first + 2], names[2])};
}

}  // namespace dsswarm::carmen_detail
