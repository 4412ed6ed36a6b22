#!/usr/bin/env bash
# One command from a fresh Debian 12 machine to a green test run: installs what
# is missing and builds twice with warnings as errors. The optimized gcc build
# (build/) runs the real-data and multi-process tests, the ones that need its
# speed; the clang build with AddressSanitizer + UndefinedBehaviorSanitizer
# (build-asan/) runs every unit test and the fuzz smoke run. Each build compiles
# only the tests it runs (DSSWARM_TESTS; configure build/ with
# -DDSSWARM_TESTS=all for every test there). Real-data tests read
# ../shared/data and skip when it is absent. Both builds are unity builds
# (CMAKE_UNITY_BUILD: up to 16 sources of a target compiled as one), which
# parses the heavy headers (Eigen, GoogleTest, nlohmann-json, CLI11) once per
# batch instead of once per source: this is what keeps the run short. Names at
# file scope must therefore be unique within a target, anonymous namespace or not.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install_deps.sh
jobs=$(nproc)

system_tests="RealData|MultiProcess"  # in test names; the rest are unit tests
unity="-DCMAKE_UNITY_BUILD=ON -DCMAKE_UNITY_BUILD_BATCH_SIZE=16"

# DSSWARM_BUILD_TESTS explicitly: scripts/demo.sh configures the same folder without tests.
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DDSSWARM_WERROR=ON -DDSSWARM_BUILD_TESTS=ON \
  -DDSSWARM_TESTS=system $unity >/dev/null
cmake --build build -j "$jobs"
(cd build && ctest --no-tests=error --output-on-failure -j "$jobs" -R "$system_tests")

# Sanitizers, with clang: one build serves the unit tests (real-data and
# multi-process tests excluded: slow under ASan, and they exercise the same
# code) and the libFuzzer targets, which then run 8 s each (scripts/fuzz.sh --smoke).
# CMake cannot switch an existing folder to another compiler: a build-asan
# left by gcc is started afresh.
grep -qs '^CMAKE_CXX_COMPILER:.*clang' build-asan/CMakeCache.txt || rm -rf build-asan
cmake -S . -B build-asan -G Ninja -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=None \
  -DCMAKE_CXX_FLAGS=-O1 -DDSSWARM_WERROR=ON -DDSSWARM_FUZZ=ON -DDSSWARM_BUILD_BENCH=OFF -DDSSWARM_TESTS=all $unity >/dev/null
cmake --build build-asan -j "$jobs"
(cd build-asan && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --no-tests=error --output-on-failure -j "$jobs" -E "$system_tests")
scripts/fuzz.sh --build build-asan --no-build --smoke
