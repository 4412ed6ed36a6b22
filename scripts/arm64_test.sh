#!/usr/bin/env bash
# Builds dsswarm for arm64 — the Raspberry Pi's architecture (Pi 3/4/5 with a
# 64-bit OS) — with Debian's cross compiler and the dependencies' arm64
# (multiarch) -dev packages, warnings as errors, and runs the tests under
# qemu-user (ctest through CMAKE_CROSSCOMPILING_EMULATOR, see
# cmake/aarch64-linux-gnu.cmake). Usage: scripts/arm64_test.sh [BUILD_DIR]
# (default build-arm64). Installs what it needs (idempotent): the arm64
# architecture for dpkg, crossbuild-essential-arm64, qemu-user, and the
# :arm64 -dev packages; Eigen, CLI11 and nlohmann-json are headers for every
# architecture, and idlc (cyclonedds-tools) runs on the host.
#
# Where it differs from the host build:
# - ROS1 bags: off (-DDSSWARM_WITH_ROSBAG=OFF). librosbag-storage-dev:arm64 is
#   not installable beside the amd64 packages (pluginlib-dev has no arm64
#   build in Debian 12). ROS 2 bags (our own reader) are in.
# - yaml-cpp, glog, gflags: their -dev and library packages are not
#   Multi-Arch: same (the arm64 package would replace the amd64 one), so their
#   arm64 .debs are unpacked into BUILD_DIR/sysroot-extra, not installed, and
#   CMake finds them there (CMAKE_PREFIX_PATH). libceres-dev is Multi-Arch:
#   same but depends on the arm64 glog and gflags -dev packages, so it is
#   unpacked too. Its CMake package links the static libceres.a; what that
#   needs (SuiteSparse, ATLAS/BLAS/LAPACK) is Multi-Arch: same and installed.
#   Under qemu the programs find the unpacked libglog and libgflags through
#   LD_LIBRARY_PATH (DSSWARM_ARM64_LIBRARY_PATH in the toolchain file).
# - Not run: the tests listed in not_run below, each for a reason of the
#   emulator's (none for a failure of the code on arm64).
set -euo pipefail
cd "$(dirname "$0")/.."
build=$(realpath -m "${1:-build-arm64}")
start=$(date +%s)

sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
if ! dpkg --print-foreign-architectures | grep -qx arm64; then
  $sudo dpkg --add-architecture arm64
  $sudo apt-get update -qq
fi
arm64_dev=(libfmt-dev libspdlog-dev libpng-dev zlib1g-dev libzstd-dev liblz4-dev libsqlite3-dev libbz2-dev
           libgtest-dev libgmock-dev libbenchmark-dev cyclonedds-dev libssl-dev
           libsuitesparse-dev libatlas-base-dev libblas-dev liblapack-dev)  # the last four for Ceres
scripts/install_deps.sh crossbuild-essential-arm64 qemu-user "${arm64_dev[@]/%/:arm64}"

# yaml-cpp, Ceres, glog and gflags for arm64, unpacked (see above). The stamp
# names the .debs unpacked, so a changed list or version unpacks afresh.
extra=$build/sysroot-extra
unpacked=(libyaml-cpp-dev libyaml-cpp0.7 libceres-dev libgoogle-glog-dev libgoogle-glog0v6
          libgflags-dev libgflags2.2)
want=$(for p in "${unpacked[@]}"; do echo "$p $(apt-cache policy "$p:arm64" | awk '/Candidate:/ {print $2}')"; done)
if [ "$(cat "$extra/.unpacked" 2> /dev/null)" != "$want" ]; then
  debs=$(mktemp -d)
  rm -rf "$extra"
  mkdir -p "$extra"
  (cd "$debs" && apt-get download -q "${unpacked[@]/%/:arm64}" > /dev/null 2>&1)
  for deb in "$debs"/*.deb; do dpkg-deb -x "$deb" "$extra"; done
  rm -rf "$debs"
  echo "$want" > "$extra/.unpacked"
fi

launcher=()
command -v ccache > /dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DDSSWARM_WERROR=ON \
  -DCMAKE_TOOLCHAIN_FILE="$PWD/cmake/aarch64-linux-gnu.cmake" -DDSSWARM_WITH_ROSBAG=OFF \
  -DCMAKE_PREFIX_PATH="$extra/usr" -DDSSWARM_ARM64_LIBRARY_PATH="$extra/usr/lib/aarch64-linux-gnu" \
  "${launcher[@]}" > /dev/null
cmake --build "$build" -j "$(nproc)"
built=$(date +%s)
file "$build/dsswarm" | grep -q "ARM aarch64" || { echo "error: $build/dsswarm is not an arm64 program" >&2; exit 1; }
not_run=(
  # Tests that start other programs: the programs are arm64 binaries, and
  # starting one from a test needs binfmt_misc, which containers usually lack
  # (posix_spawn fails, exit 127, or the peer never says "ready").
  ReplayTest cli_bad_input MultiProcess SecurityDdsTest SecurityRestart HandshakeWatchdogDdsTest
  SwarmToolsTest ReplayScenario
  # The same code as the unit tests on the real logs: minutes under emulation.
  RealData
  # Two robots on threads, fed at 3x real time, with a 2 s heartbeat timeout:
  # emulated, they are too slow for it and drop each other ("no heartbeat
  # from b for 2 s"). A wall-clock limit, not arm64 code.
  AgentRuntime.RobotsOnTheirOwnThreadsDecideAsTheInProcessSwarmDoes
)
exclude=$(IFS='|'; echo "${not_run[*]}")
status=0
(cd "$build" && ctest --output-on-failure --no-tests=error -j "$(nproc)" -E "$exclude") || status=$?
echo "arm64: build $((built - start)) s, tests $(($(date +%s) - built)) s"
exit "$status"
