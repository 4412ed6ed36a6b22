#!/usr/bin/env bash
# One command from a fresh Debian 12 machine to a green test run: installs what
# is missing, builds with warnings as errors, and runs every test through ctest;
# then rebuilds with AddressSanitizer + UndefinedBehaviorSanitizer and runs the
# unit tests again. Real-data tests read ../shared/data and skip when it is absent.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install_deps.sh
jobs=$(nproc)

# DSSWARM_BUILD_TESTS explicitly: scripts/demo.sh configures the same folder without tests.
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DDSSWARM_WERROR=ON -DDSSWARM_BUILD_TESTS=ON >/dev/null
cmake --build build -j "$jobs"
(cd build && ctest --no-tests=error --output-on-failure -j "$jobs")

# Sanitizers: the unit tests (real-data tests excluded: they are slow under ASan
# and exercise the same code).
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_FLAGS=-O1 -DDSSWARM_WERROR=ON -DDSSWARM_SANITIZE=ON -DDSSWARM_BUILD_BENCH=OFF >/dev/null
cmake --build build-asan -j "$jobs"
(cd build-asan && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --no-tests=error --output-on-failure -j "$jobs" -E RealData)
