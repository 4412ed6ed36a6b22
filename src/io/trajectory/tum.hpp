#pragma once
// TUM RGB-D trajectory files ("timestamp x y z qx qy qz qw", one pose per
// line), the format evo, the TUM benchmark tools and most SLAM packages read.
// Our poses are planar: z = 0 and the quaternion is a pure yaw rotation.
#include <filesystem>
#include <istream>
#include <string>
#include <vector>

#include "geometry/pose2.hpp"

namespace dsswarm {

struct StampedPose {
  double timestamp = 0.0;  // seconds, in the log's own clock
  Pose2 pose;
};

// In file order. Not necessarily sorted by time: real logs (intel) have
// timestamps that run backwards, and file order is the true order.
using Trajectory = std::vector<StampedPose>;

// Writes `trajectory` atomically (write_file_atomically), with a leading
// "# timestamp x y z qx qy qz qw" comment. Throws InputError naming the file
// and the entry if a pose or timestamp is not finite (nothing is written then).
void write_tum(const std::filesystem::path& path, const Trajectory& trajectory);

// The file write_tum writes, as text; errors name `path`.
std::string format_tum(const std::filesystem::path& path, const Trajectory& trajectory);

// Reads a TUM file, keeping file order. Blank lines and '#' comments are
// skipped. Yaw comes from the full quaternion, so 3D trajectories written by
// other tools are projected onto the plane (z, roll and pitch are dropped).
// Throws InputError naming file:line (and the field) for malformed lines.
Trajectory read_tum(const std::filesystem::path& path);

// Same, from a stream; `source_name` stands for the file name in errors.
Trajectory read_tum(std::istream& in, const std::string& source_name);

}  // namespace dsswarm
