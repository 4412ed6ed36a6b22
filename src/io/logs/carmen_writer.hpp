#pragma once
// Writer for CARMEN text logs: `# PARAM` geometry lines, then one FLASER
// record per scan. read_carmen(write_carmen(scans)) gives back the same scans
// (numbers are written in their shortest exact form, never rounded).
#include <filesystem>
#include <string>
#include <vector>

#include "sensor/laser_scan.hpp"

namespace dsswarm {

// Writes `scans` (in the given order) to `path`, atomically. `comment` goes
// into the header, one `#` line per line of text.
//
// FLASER carries one beam layout and laser offset for the whole file, so
// every scan must share angle_min, angle_increment, range_min, range_max and
// laser_offset (beam counts may differ); otherwise InputError, as for an empty
// `scans`, a scan without readings, or a non-finite timestamp, pose or geometry. The laser pose written is odometry ⊕ laser_offset. A scan without
// odometry is written with zero poses; if no scan has odometry the header says
// so (`# PARAM odometry none`) and read_carmen gives the scans no odometry.
void write_carmen(const std::filesystem::path& path, const std::vector<LaserScan>& scans,
                  const std::string& comment = "");

// The file write_carmen writes, as text; errors name `path`.
std::string format_carmen(const std::filesystem::path& path, const std::vector<LaserScan>& scans,
                          const std::string& comment = "");

}  // namespace dsswarm
