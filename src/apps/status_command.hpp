#pragma once
// `dsswarm status [--watch]`: listens to the swarm's heartbeats and prints a
// table of its agents (scans/s, scans processed and skipped, peers known,
// encounters, last merge, map version, messages refused). It only listens:
// agents never learn of it.
#include <CLI/CLI.hpp>

namespace dsswarm {

void add_status_command(CLI::App& app);

}  // namespace dsswarm
