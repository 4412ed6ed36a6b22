#!/usr/bin/env bash
# Installs the Debian 12 packages dsswarm needs, only those missing (idempotent).
# Extra package names given as arguments are installed the same way (the
# measurement scripts' own tools: bench/compare.sh, scripts/arm64_test.sh).
# apt may never remove a package to make room (--no-remove): a conflict stops.
set -euo pipefail
packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev libcli11-dev nlohmann-json3-dev libspdlog-dev libfmt-dev
  libpng-dev zlib1g-dev libzstd-dev libyaml-cpp-dev libsqlite3-dev liblz4-dev libceres-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  librosbag-storage-dev libsensor-msgs-dev libnav-msgs-dev libtf2-msgs-dev libbz2-dev
  cyclonedds-dev cyclonedds-tools libssl-dev
  clang libclang-rt-14-dev llvm  # sanitizer build + libFuzzer; llvm-symbolizer for readable reports
  iproute2 nftables  # the packet-loss tests and scripts/fault_table.sh (network namespaces, loss)
  "$@"
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
echo "installing: ${missing[*]}" >&2
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends --no-remove "${missing[@]}" >/dev/null
