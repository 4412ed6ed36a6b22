#pragma once
// A command's input log (run, filter, replay, agent --log): read, its quirks
// logged as warnings, refused when it holds no laser scan.
#include <string>

#include "io/logs/log_reader.hpp"

namespace dsswarm {

SensorLog read_input_log(const std::string& path, const LogReadOptions& options = {});

}  // namespace dsswarm
