// carmen2rawlog LOG OUT_PREFIX
//
// Writes a CARMEN log (read by dsswarm's reader: file order, `# PARAM`
// geometry, laser offset) as an MRPT rawlog for icp-slam and rbpf-slam, every
// record stamped with the scan's own timestamp: MRPT 2.5.8's carmen2rawlog
// stamps them with the time of conversion instead, and icp-slam's pose
// extrapolation then never lines up with the odometry.
//   OUT_PREFIX.rawlog  actions and sensory frames: per scan the odometry
//                      increment since the previous scan
//                      (CActionRobotMovement2D, MRPT's default Gaussian motion
//                      model), then the scan (CObservation2DRangeScan). The
//                      observations-only format carmen2rawlog writes crashes
//                      rbpf-slam.
//   OUT_PREFIX.stamps  one line per scan, its timestamp (6 decimals): the time
//                      of each step of the apps' log_estimated_path.txt.
#include <mrpt/io/CFileOutputStream.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/serialization/CArchive.h>

#include <cstdio>
#include <exception>
#include <fstream>
#include <string>

#include "io/logs/carmen_reader.hpp"

namespace {

using dsswarm::LaserScan;
using dsswarm::Pose2;

mrpt::obs::CObservation2DRangeScan::Ptr to_mrpt(const LaserScan& scan) {
  auto obs = mrpt::obs::CObservation2DRangeScan::Create();
  const std::size_t n = scan.ranges.size();
  obs->sensorLabel = "LASER";
  obs->timestamp = mrpt::Clock::fromDouble(scan.timestamp);
  obs->rightToLeft = true;
  obs->aperture = static_cast<float>(scan.angle_increment * static_cast<double>(n - 1));
  obs->maxRange = static_cast<float>(scan.range_max);
  // MRPT's beams span [-aperture/2, aperture/2] about the sensor's x axis:
  // an off-centre scan turns the sensor instead.
  const double yaw = scan.laser_offset.theta + scan.angle_min + 0.5 * obs->aperture;
  obs->sensorPose = mrpt::poses::CPose3D(scan.laser_offset.x, scan.laser_offset.y, 0.0, yaw, 0.0, 0.0);
  obs->resizeScan(n);
  for (std::size_t i = 0; i < n; ++i) {
    obs->setScanRange(i, scan.is_valid(scan.ranges[i]) ? scan.ranges[i] : obs->maxRange);
    obs->setScanRangeValidity(i, scan.is_valid(scan.ranges[i]));
  }
  return obs;
}

mrpt::poses::CPose2D to_mrpt(const Pose2& p) { return {p.x, p.y, p.theta}; }

mrpt::obs::CActionCollection odometry_action(const Pose2& increment, double timestamp) {
  mrpt::obs::CActionRobotMovement2D move;
  move.computeFromOdometry(to_mrpt(increment), mrpt::obs::CActionRobotMovement2D::TMotionModelOptions());
  move.timestamp = mrpt::Clock::fromDouble(timestamp);
  mrpt::obs::CActionCollection actions;
  actions.insert(move);
  return actions;
}

void convert(const std::string& log_path, const std::string& prefix) {
  const dsswarm::SensorLog log = dsswarm::read_carmen(log_path);
  if (log.scans.empty()) throw std::runtime_error(log_path + ": no laser scans");
  mrpt::io::CFileOutputStream file(prefix + ".rawlog");
  auto rawlog = mrpt::serialization::archiveFrom(file);
  std::ofstream stamps(prefix + ".stamps");
  Pose2 previous = log.scans.front().odometry.value_or(Pose2());
  for (const LaserScan& scan : log.scans) {
    if (!scan.odometry) throw std::runtime_error(log_path + ": a scan without odometry");
    mrpt::obs::CSensoryFrame frame;
    frame.insert(to_mrpt(scan));
    rawlog << odometry_action(previous.inverse() * *scan.odometry, scan.timestamp) << frame;
    previous = *scan.odometry;
    char line[64];
    std::snprintf(line, sizeof line, "%.6f\n", scan.timestamp);
    stamps << line;
  }
  if (!stamps) throw std::runtime_error(prefix + ".stamps: write failed");
  std::fprintf(stderr, "%s: %zu scans -> %s.rawlog\n", log_path.c_str(), log.scans.size(), prefix.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: carmen2rawlog LOG OUT_PREFIX\n");
    return 2;
  }
  try {
    convert(argv[1], argv[2]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
