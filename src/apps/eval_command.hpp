#pragma once
// `dsswarm eval relations|ate ...`: score a trajectory file. Each prints a
// human-readable summary and, as its last output line, one JSON object.
#include <CLI/CLI.hpp>

namespace dsswarm {

// Registers the `eval` subcommand (with `relations` and `ate`) on `app`.
// Input problems surface as exceptions (InputError, ConfigError) from the
// subcommand callbacks, for main() to report.
void add_eval_command(CLI::App& app);

}  // namespace dsswarm
