#include "apps/log_input.hpp"

#include <spdlog/spdlog.h>

#include "common/errors.hpp"

namespace dsswarm {

SensorLog read_input_log(const std::string& path, const LogReadOptions& options) {
  SensorLog log = read_log(path, options);
  for (const std::string& w : log.warnings) spdlog::warn("{}", w);
  if (log.scans.empty()) throw InputError(path + ": no laser scans");
  return log;
}

}  // namespace dsswarm
