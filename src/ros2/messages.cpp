#include "ros2/messages.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "common/errors.hpp"

namespace dsswarm::ros2 {

double to_seconds(const Time& t) {
  return static_cast<double>(t.sec) + static_cast<double>(t.nanosec) * 1e-9;
}

Time time_from_seconds(double seconds) {
  constexpr double kNanosPerSecond = 1e9;
  const double whole = std::floor(seconds);
  if (!std::isfinite(seconds) || whole < std::numeric_limits<std::int32_t>::min() ||
      whole > std::numeric_limits<std::int32_t>::max()) {
    throw InputError(fmt::format("time {} s does not fit builtin_interfaces/Time", seconds));
  }
  auto sec = static_cast<std::int64_t>(whole);
  auto nanosec = std::llround((seconds - whole) * kNanosPerSecond);
  if (nanosec >= static_cast<long long>(kNanosPerSecond)) {  // rounded up to the next second
    ++sec;
    nanosec = 0;
  }
  if (sec > std::numeric_limits<std::int32_t>::max()) {
    throw InputError(fmt::format("time {} s does not fit builtin_interfaces/Time", seconds));
  }
  return {static_cast<std::int32_t>(sec), static_cast<std::uint32_t>(nanosec)};
}

}  // namespace dsswarm::ros2
