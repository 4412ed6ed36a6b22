#pragma once
// Reader for CARMEN text logs (.log, .clf; plain or gzip-compressed).
//
// Laser records understood:
//   FLASER n r1..rn x y theta odom_x odom_y odom_theta timestamp host logger_timestamp
//   RLASER (same layout; rear laser)
//   ROBOTLASER1 laser_type start_angle fov angular_res max_range accuracy remission_mode
//               n r1..rn k rem1..remk laser_x laser_y laser_theta robot_x robot_y robot_theta
//               tv rv forward_safety side_safety turn_axis timestamp host logger_timestamp
// where x y theta / laser_* is the laser pose in the odometry frame and
// odom_* / robot_* the robot base pose by odometry.
// One laser stream is read: FLASER if the file has any, else ROBOTLASER1, else
// RLASER (logs often carry the same scans in two formats).
// ODOM records are validated and checked for time order, nothing more: each
// laser record carries its own odometry pose.
//
// `# PARAM key value` comment lines (written by our converter and by
// write_carmen) give the scan geometry for the whole file:
//   laser_angle_min, laser_angle_max, laser_angle_increment, laser_num_beams,
//   laser_range_min, laser_range_max, laser_offset_x, laser_offset_y, laser_offset_theta
// (radians, metres). Classic logs have none of these; see BeamConvention.
// Without laser_range_max, range_max is 80 m (the SICK LMS limit: classic logs
// store "no return" as 81.91 m); without laser_range_min, range_min is 0.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "geometry/pose2.hpp"
#include "sensor/laser_scan.hpp"

namespace dsswarm {

struct CarmenOptions {
  // How the beam angles of FLASER/RLASER records are laid out (ROBOTLASER1
  // records state their own start angle and resolution, which always win).
  enum class BeamConvention {
    FromParams,  // `# PARAM` geometry if the file has it, else Classic
    Classic,     // CARMEN's own: 1° steps for 180 beams, 0.5° for 360/361, 0.25° for 720/721, centred
    Span180,     // angle_min = -pi/2, increment = pi/(n-1): the beams span exactly 180°
  };
  BeamConvention beams = BeamConvention::FromParams;
  // Laser mounting pose in the robot base frame; overrides both the `# PARAM`
  // offsets and the offset derived from the laser and robot poses in the records.
  std::optional<Pose2> laser_offset;
};

struct BeamGeometry {
  double angle_min = 0.0;
  double angle_increment = 0.0;
};

// The beam layouts of the two fixed conventions for an n-beam scan (n >= 1).
BeamGeometry classic_beam_geometry(std::size_t n);
BeamGeometry span180_beam_geometry(std::size_t n);

// Range used as range_max when a log states none.
inline constexpr double kCarmenDefaultRangeMax = 80.0;

// Reads the whole log in file order (timestamps that run backwards are kept
// where they are and reported in SensorLog::warnings). Throws InputError
// naming the file, and the line and field where it applies, for a missing,
// truncated or malformed file or one without laser scans.
SensorLog read_carmen(const std::filesystem::path& path, const CarmenOptions& options = {});

// The same for a log already in memory (uncompressed text, lines ending in
// \n or \r\n); `source_name` stands for the file name in errors and warnings.
SensorLog parse_carmen(std::string_view text, const std::string& source_name, const CarmenOptions& options = {});

}  // namespace dsswarm
