#pragma once
// `dsswarm filter LOG --out FILTERED_LOG ...`: runs the scan filter
// (src/filter) over a log and writes the kept scans as a CARMEN log. Prints
// the counts and, as its last output line, one JSON object with scans_read,
// scans_kept, scans_dropped, drop_ratio (0-1) and filter_seconds.
#include <CLI/CLI.hpp>

namespace dsswarm {

// Registers the `filter` subcommand on `app`. Problems surface as exceptions
// (InputError, ConfigError) from the subcommand callback, for main() to report.
void add_filter_command(CLI::App& app);

}  // namespace dsswarm
