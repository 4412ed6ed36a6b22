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
# - yaml-cpp: libyaml-cpp-dev is not Multi-Arch: same (its arm64 package would
#   replace the amd64 one), so the arm64 .debs are unpacked into
#   BUILD_DIR/sysroot-extra, not installed. (libceres-dev, for later, is the
#   same: it and glog/gflags would replace the amd64 packages.)
# - Not run: tests that start other programs (ReplayTest, cli_bad_input): the
#   programs they start are arm64 binaries, and running those from a test
#   needs binfmt_misc, which containers usually lack; and the RealData tests
#   (the same code as the unit tests on bigger input, minutes under emulation).
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
           libgtest-dev libgmock-dev libbenchmark-dev cyclonedds-dev libssl-dev)
scripts/install_deps.sh crossbuild-essential-arm64 qemu-user "${arm64_dev[@]/%/:arm64}"

# yaml-cpp for arm64, unpacked (see above).
extra=$build/sysroot-extra
if [ ! -f "$extra/usr/lib/aarch64-linux-gnu/cmake/yaml-cpp/yaml-cpp-config.cmake" ]; then
  debs=$(mktemp -d)
  mkdir -p "$extra"
  (cd "$debs" && apt-get download -q libyaml-cpp-dev:arm64 libyaml-cpp0.7:arm64 > /dev/null 2>&1)
  for deb in "$debs"/*.deb; do dpkg-deb -x "$deb" "$extra"; done
  rm -rf "$debs"
fi

launcher=()
command -v ccache > /dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DDSSWARM_WERROR=ON \
  -DCMAKE_TOOLCHAIN_FILE="$PWD/cmake/aarch64-linux-gnu.cmake" -DDSSWARM_WITH_ROSBAG=OFF \
  -Dyaml-cpp_DIR="$extra/usr/lib/aarch64-linux-gnu/cmake/yaml-cpp" "${launcher[@]}" > /dev/null
cmake --build "$build" -j "$(nproc)"
built=$(date +%s)
file "$build/dsswarm" | grep -q "ARM aarch64" || { echo "error: $build/dsswarm is not an arm64 program" >&2; exit 1; }
(cd "$build" && ctest --output-on-failure --no-tests=error -j "$(nproc)" -E 'RealData|ReplayTest|cli_bad_input')
echo "arm64: build $((built - start)) s, tests $(($(date +%s) - built)) s"
