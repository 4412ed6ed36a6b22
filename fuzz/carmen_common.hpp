#pragma once
// Shared by the two CARMEN targets: the seed logs (the shapes the unit tests
// of src/io/logs/carmen_reader*_test.cpp feed the reader, and the first
// records of the shared logs) and what a log read without error guarantees.
#include <cmath>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "fuzz_support.hpp"
#include "sensor/laser_scan.hpp"

namespace dsswarm::fuzz {

inline std::vector<std::pair<std::string, std::string>> carmen_seed_logs(const Seeds& seeds) {
  std::vector<std::pair<std::string, std::string>> logs = {
      {"params",
       "# PARAM laser_format FLASER\n# PARAM laser_angle_min -1.25\n# PARAM laser_angle_increment 0.5\n"
       "# PARAM laser_num_beams 5\n# PARAM laser_range_min 0.1\n# PARAM laser_range_max 30\n"
       "# PARAM laser_offset_x 0.25\n# PARAM laser_offset_y -0.05\n# PARAM laser_offset_theta 0.1\n"
       "# PARAM odometry none\n"
       "FLASER 5 1 2 3 4 5 1.2 1.9 0.6 1.0 2.0 0.5 10.0 host -90.0\n"},
      {"flaser-odom",
       "ODOM 0 0 0 0 0 0 0.5 host 0.5\nFLASER 3 1 2 3 0 0 0 0 0 0 1.0 host 0\n"
       "ODOM 0.1 0 0 0 0 0 1.5 host 1.5\nFLASER 3 1 nan inf 0.1 0 0 0.1 0 0 2.0 host 1\n"
       "FLASER 3 1 2 3 0.2 0 0 0.2 0 0 1.5 host 2\n"},
      {"rlaser-crlf", "# PARAM laser_range_max 12\r\nRLASER\t3 1 2 3\t0 0 0 0 0 0 5.0 host 0\r\n  \r\n"},
      {"robotlaser",
       "ROBOTLASER1 0 -1.0 2.0 0.5 40.0 0.01 0 5 1 2 3 4 5 2 0.5 0.6 0.1 0 0 0 0 0 0.1 0.2 0.3 0.4 0.5 7.25 "
       "host 0.5\n"
       "FLASER 0 0 0 0 0 0 0 8.0 host 0\n"},
      {"known-and-unknown",
       "PARAM robot_frontlaser_offset 0.0 host 0\nSYNC foo\nTRUEPOS 1 2 3 4 5 6 1.0 host 1.0\n"
       "MYSTERY 1 2 3\nFLASER 2 1 2 0 0 0 0 0 0 3.0 host 0\n"},
  };
  // Real logs: the first records (a CARMEN line of 180 or 361 beams is 1-2.5 KB).
  // The converted log's free-text header is dropped, its `# PARAM` lines kept.
  const std::string head = seeds.shared_text("carmen/intel.log.gz", 3000);
  std::string intel;
  for (std::string_view rest = head; !rest.empty();) {
    const std::size_t newline = rest.find('\n');
    const std::string_view line = rest.substr(0, newline == std::string_view::npos ? rest.size() : newline + 1);
    rest.remove_prefix(line.size());
    if (line.front() != '#' || line.starts_with("# PARAM")) intel += line;
  }
  if (!intel.empty()) logs.emplace_back("intel", std::move(intel));
  if (std::string clf = seeds.shared_text("clf/mit-csail.clf.gz", 3000); !clf.empty()) {
    logs.emplace_back("mit-csail-clf", std::move(clf));
  }
  return logs;
}

// Record types, `# PARAM` keys and the values that change how a line reads.
inline std::vector<std::string> carmen_dictionary() {
  return {"FLASER ", "RLASER ", "ROBOTLASER1 ", "ODOM ", "SYNC ", "TRUEPOS ", "# PARAM ", "laser_angle_min ",
          "laser_angle_max ", "laser_angle_increment ", "laser_num_beams ", "laser_range_min ",
          "laser_range_max ", "laser_offset_x ", "laser_offset_y ", "laser_offset_theta ", "odometry none",
          " host ", " nan", " inf", " -inf", " 1e308", " -0", " 81.91", "\r\n", "\t"};
}

inline void check_log(const SensorLog& log) {
  check(!log.scans.empty(), "a log without scans was accepted");
  for (const LaserScan& scan : log.scans) {
    check(!scan.ranges.empty(), "a scan without readings was accepted");
    check(std::isfinite(scan.timestamp), "a scan timestamp is not finite");
    check(std::isfinite(scan.angle_min) && std::isfinite(scan.angle_increment), "scan geometry is not finite");
    check(scan.range_max > scan.range_min, "range_max is not above range_min");
  }
}

}  // namespace dsswarm::fuzz
