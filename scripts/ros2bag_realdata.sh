#!/usr/bin/env bash
# The shared CARMEN logs converted to ROS 2 bags (.db3 and zstd-chunked .mcap)
# must give the CARMEN logs' scans and SLAM trajectories. ctest runs
# mit-csail; this runs all three (intel takes a few minutes) and prints the
# figures: worst pose difference bag vs CARMEN, and both relation metrics.
# Usage: scripts/ros2bag_realdata.sh [BUILD_DIR]   (default build/)
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$here/build}
cmake --build "$build" --target io_rosbag2_realdata_test >/dev/null
DSSWARM_ROS2BAG_ALL_LOGS=1 "$build/tests/io_rosbag2_realdata_test" | grep -E '^\[ *(figures|FAILED|PASSED|SKIPPED)'
