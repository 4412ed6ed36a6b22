#pragma once
// `--start-at UNIX_TIME`: the wall-clock moment of clock 0, so that the
// replays, the proximity source and the agents of one launch (started one
// after the other) play on one clock.
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <optional>

#include "common/errors.hpp"

namespace dsswarm {

inline std::optional<std::chrono::system_clock::time_point> start_time(const std::optional<double>& unix_seconds) {
  if (!unix_seconds) return std::nullopt;
  if (!(std::isfinite(*unix_seconds) && *unix_seconds > 0.0))
    throw ConfigError(fmt::format("--start-at {} is not a unix time (seconds since 1970)", *unix_seconds));
  return std::chrono::system_clock::time_point(
      std::chrono::duration_cast<std::chrono::system_clock::duration>(std::chrono::duration<double>(*unix_seconds)));
}

}  // namespace dsswarm
