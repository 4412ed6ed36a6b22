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

# Sanitizers, with clang: one build serves the unit tests (real-data tests
# excluded: they are slow under ASan and exercise the same code) and the
# libFuzzer targets, which then run 8 s each (scripts/fuzz.sh --smoke).
# CMake cannot switch an existing folder to another compiler: a build-asan
# left by gcc is started afresh.
grep -qs '^CMAKE_CXX_COMPILER:.*clang' build-asan/CMakeCache.txt || rm -rf build-asan
cmake -S . -B build-asan -G Ninja -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=None \
  -DCMAKE_CXX_FLAGS=-O1 -DDSSWARM_WERROR=ON -DDSSWARM_FUZZ=ON -DDSSWARM_BUILD_BENCH=OFF >/dev/null
cmake --build build-asan -j "$jobs"
(cd build-asan && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --no-tests=error --output-on-failure -j "$jobs" -E "RealData|MultiProcess")
scripts/fuzz.sh --build build-asan --no-build --smoke
