// dsswarm: decentralized multi-robot 2D laser SLAM with Dempster–Shafer grids.
#include <CLI/CLI.hpp>
#include <fmt/core.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <cstdlib>
#include <exception>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "apps/agent_command.hpp"
#include "apps/eval_command.hpp"
#include "apps/filter_command.hpp"
#include "apps/launch_command.hpp"
#include "apps/replay_command.hpp"
#include "apps/keys_command.hpp"
#include "apps/proximity_command.hpp"
#include "apps/run_command.hpp"
#include "apps/status_command.hpp"
#include "apps/swarm_command.hpp"
#include "apps/trigger_command.hpp"
#include "common/errors.hpp"

namespace {

// glibc gives each thread that allocates its own heap (arena) and keeps
// what was freed there: a robot process (scan, swarm, loop-closing, map and
// DDS threads) peaked at about three times the memory it used; two arenas
// cost no CPU (docs/swarm_processes.md). MALLOC_ARENA_MAX in the
// environment still wins.
constexpr int kMallocArenas = 2;

void limit_malloc_arenas() {
#if defined(__GLIBC__)
  if (!std::getenv("MALLOC_ARENA_MAX")) mallopt(M_ARENA_MAX, kMallocArenas);
#endif
}

}  // namespace

int main(int argc, char** argv) {
  limit_malloc_arenas();
  // Warnings go to stderr as "warning: ...", like errors; stdout carries results.
  spdlog::set_default_logger(spdlog::stderr_color_st("dsswarm"));
  spdlog::set_pattern("%^%l%$: %v");
  CLI::App app{"dsswarm: decentralized multi-robot 2D laser SLAM on small computers"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "dsswarm 0.1.0");
  dsswarm::add_swarm_demo_command(app);
  dsswarm::add_swarm_command(app);
  dsswarm::add_run_command(app);
  dsswarm::add_filter_command(app);
  dsswarm::add_eval_command(app);
  dsswarm::add_config_command(app);
  dsswarm::add_replay_command(app);
  dsswarm::add_keys_command(app);
  dsswarm::add_agent_command(app);
  dsswarm::add_launch_command(app);
  dsswarm::add_proximity_command(app);
  dsswarm::add_trigger_command(app);
  dsswarm::add_status_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version arrive as "errors" that exit 0; the rest are
    // command-line mistakes: exit 2 like any other configuration error.
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(e);
    fmt::print(stderr, "error: {}\nRun with --help for more information.\n", e.what());
    return 2;
  } catch (const dsswarm::InputError& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return 1;
  } catch (const dsswarm::ConfigError& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return 1;
  }
  return 0;
}
