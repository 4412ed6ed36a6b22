#!/usr/bin/env bash
# Installs the Debian 12 packages dsswarm needs, only those missing (idempotent).
set -euo pipefail
packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev libcli11-dev nlohmann-json3-dev libspdlog-dev libfmt-dev
  libpng-dev zlib1g-dev libzstd-dev libyaml-cpp-dev libsqlite3-dev liblz4-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  librosbag-storage-dev libsensor-msgs-dev libnav-msgs-dev libtf2-msgs-dev libbz2-dev
  cyclonedds-dev cyclonedds-tools libssl-dev
  iproute2 nftables  # the packet-loss tests and scripts/fault_table.sh (network namespaces, loss)
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
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
