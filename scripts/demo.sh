#!/usr/bin/env bash
# One command from a fresh Debian 12 machine to a SLAM result: installs what is
# missing, builds (Release), and runs the built-in simulated swarm demo.
# Outputs land in out/demo (swarm.png, encounters.json, agents/*, joint/*, stats.json).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install_deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DDSSWARM_BUILD_TESTS=OFF >/dev/null
cmake --build build --target dsswarm
./build/dsswarm demo --out out/demo "$@"
