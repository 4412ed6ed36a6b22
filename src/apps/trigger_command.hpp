#pragma once
// `dsswarm trigger A B`: tells robots A and B that they are near each other,
// now (a Proximity message with NaN stamps), with a fresh encounter id, then
// exits. For a person at a terminal, or the glue script of a real proximity
// sensor (UWB, BLE, a camera).
#include <CLI/CLI.hpp>

namespace dsswarm {

void add_trigger_command(CLI::App& app);

}  // namespace dsswarm
