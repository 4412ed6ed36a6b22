#include "io/trajectory/text_fields.hpp"

#include <charconv>
#include <cmath>
#include <system_error>

#include <fmt/format.h>

#include "common/errors.hpp"

namespace dsswarm {

std::ifstream open_text_input(const std::filesystem::path& path, std::string_view what) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) {
    throw InputError(fmt::format("cannot open {} file {}: no such file", what, path.string()));
  }
  // An ifstream happily "opens" a directory on Linux and then reads nothing.
  if (std::filesystem::is_directory(path, ec)) {
    throw InputError(fmt::format("cannot read {} file {}: it is a directory", what, path.string()));
  }
  std::ifstream in(path);
  if (!in) throw InputError(fmt::format("cannot open {} file {}: permission denied or unreadable", what, path.string()));
  return in;
}

std::string_view strip_carriage_return(std::string_view line) {
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  return line;
}

namespace {
bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }
}  // namespace

bool is_blank_or_comment(std::string_view line) {
  for (const char c : line) {
    if (is_space(c)) continue;
    return c == '#';
  }
  return true;
}

void split_fields(std::string_view line, std::vector<std::string_view>& out) {
  out.clear();
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_space(line[i])) ++i;
    const std::size_t start = i;
    while (i < line.size() && !is_space(line[i])) ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
}

std::vector<std::string_view> split_fields(std::string_view line) {
  std::vector<std::string_view> fields;
  split_fields(line, fields);
  return fields;
}

double parse_finite_field(std::string_view token, std::string_view where, std::string_view field) {
  std::string_view digits = token;
  // from_chars rejects an explicit '+', which some writers emit; accept it.
  if (digits.size() > 1 && digits[0] == '+' && digits[1] != '-' && digits[1] != '+') digits.remove_prefix(1);
  double value = 0.0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (ec == std::errc::result_out_of_range) {
    throw InputError(fmt::format("{}: field '{}' is out of range: '{}'", where, field, token));
  }
  if (ec != std::errc() || end != digits.data() + digits.size() || digits.empty()) {
    throw InputError(fmt::format("{}: field '{}' is not a number: '{}'", where, field, token));
  }
  if (!std::isfinite(value)) {
    throw InputError(fmt::format("{}: field '{}' is not finite: '{}'", where, field, token));
  }
  return value;
}

void for_each_data_line(std::istream& in, const std::string& source,
                        const std::function<void(std::string_view line, const std::string& where)>& on_line) {
  std::string raw;
  std::size_t line_number = 0;
  while (std::getline(in, raw)) {
    ++line_number;
    const std::string_view line = strip_carriage_return(raw);
    if (is_blank_or_comment(line)) continue;
    on_line(line, fmt::format("{}:{}", source, line_number));
  }
  if (in.bad()) throw InputError(fmt::format("{}: read error after line {}", source, line_number));
}

}  // namespace dsswarm
