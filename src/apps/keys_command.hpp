#pragma once
// `dsswarm keys init|add|revoke`: the swarm's DDS Security material (a CA,
// the signed governance, each robot's certificate, key and signed
// permissions, the revocation list). See docs/security.md.
#include <CLI/CLI.hpp>

namespace dsswarm {

// Registers the `keys` subcommand (with `init`, `add`, `revoke`) on `app`.
// Problems surface as InputError/ConfigError from the callbacks, for main().
void add_keys_command(CLI::App& app);

}  // namespace dsswarm
