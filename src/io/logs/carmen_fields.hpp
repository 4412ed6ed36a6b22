#pragma once
// Field-level parsing for the CARMEN reader: reading numbers from a record's
// fields (split by io/trajectory/text_fields.hpp), with errors that name the
// file, line, record and field. Internal to carmen_reader.cpp (not part of
// carmen_reader.hpp).
#include <array>
#include <charconv>
#include <cstddef>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "geometry/pose2.hpp"

namespace dsswarm::carmen_detail {

using Tokens = std::vector<std::string_view>;

// Parses the whole token or nothing ("1.5x" is not a number).
template <class T>
bool parse_whole(std::string_view token, T& value) {
  const char* first = token.data();
  const char* last = first + token.size();
  // from_chars, unlike strtod, rejects a leading '+'.
  if (last - first > 1 && *first == '+' && first[1] != '-') ++first;
  const auto [end, ec] = std::from_chars(first, last, value);
  return ec == std::errc() && end == last;
}

// Keeps error messages readable when a binary file is fed in.
std::string shown(std::string_view token);

// Where a record came from, for error messages: "file:line: RECORD: ...".
struct Where {
  const std::string& file;
  std::size_t line;
  std::string_view record;

  [[noreturn]] void fail(std::string_view message) const;
};

double number_field(const Where& where, std::string_view token, std::string_view field);
double finite_field(const Where& where, std::string_view token, std::string_view field);
std::size_t count_field(const Where& where, std::string_view token, std::string_view field);

// Ranges may be "nan", "inf" or negative: kept as they are (LaserScan treats
// them as invalid) and counted for a warning.
void read_ranges(const Where& where, const Tokens& fields, std::size_t first, std::size_t n,
                 std::vector<float>& ranges);

Pose2 pose_fields(const Where& where, const Tokens& fields, std::size_t first,
                  const std::array<std::string_view, 3>& names);

}  // namespace dsswarm::carmen_detail
