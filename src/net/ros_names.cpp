#include "net/ros_names.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "common/errors.hpp"

namespace dsswarm::net {
namespace {

bool valid_token(std::string_view token) {
  if (token.empty() || (token.front() >= '0' && token.front() <= '9')) return false;
  for (const char c : token) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
    if (!ok) return false;
  }
  return true;
}

// Checks every '/'-separated token of `path` (without leading '/').
void check_tokens(std::string_view path, std::string_view what, std::string_view original) {
  std::size_t start = 0;
  while (start <= path.size()) {
    const std::size_t end = std::min(path.find('/', start), path.size());
    if (!valid_token(path.substr(start, end - start))) {
      throw ConfigError(fmt::format("invalid ROS {} '{}': tokens are letters, digits and '_', not starting with a "
                                    "digit, separated by single '/'",
                                    what, original));
    }
    start = end + 1;
  }
}

}  // namespace

std::string normalize_namespace(std::string_view ns) {
  std::string_view body = ns;
  if (!body.empty() && body.front() == '/') body.remove_prefix(1);
  if (!body.empty() && body.back() == '/') body.remove_suffix(1);
  if (body.empty()) return "/";
  check_tokens(body, "namespace", ns);
  return fmt::format("/{}", body);
}

std::string ros_fully_qualified_name(std::string_view ns, std::string_view name) {
  if (name.empty() || name.front() == '~' || name.back() == '/') {
    throw ConfigError(fmt::format("invalid ROS topic name '{}' (empty, private '~' or ending in '/')", name));
  }
  if (name.front() == '/') {
    check_tokens(name.substr(1), "topic name", name);
    return std::string(name);
  }
  check_tokens(name, "topic name", name);
  const std::string base = normalize_namespace(ns);
  return base == "/" ? fmt::format("/{}", name) : fmt::format("{}/{}", base, name);
}

std::string ros_topic_name(std::string_view ns, std::string_view name) {
  return fmt::format("rt{}", ros_fully_qualified_name(ns, name));
}

std::string_view strip_frame_slash(std::string_view frame) {
  if (!frame.empty() && frame.front() == '/') frame.remove_prefix(1);
  return frame;
}

}  // namespace dsswarm::net
