#pragma once
// A robot process's state on disk, so that after a crash `agent --resume`
// goes on where it was: DIR/checkpoint.dsmap (its own map and every layer it
// knows, in its frame) and DIR/checkpoint.json (pose, counts), each written
// atomically, the map first; DIR/trajectory.tum keeps the poses so far.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "geometry/pose2.hpp"
#include "io/trajectory/tum.hpp"
#include "swarm/map_snapshot.hpp"

namespace dsswarm::agent {

struct Checkpoint {
  std::string name;
  MapSnapshot snapshot;  // layers[0]: the robot's own map
  Pose2 pose;            // in its own map frame, at `stamp`
  double stamp = 0.0;
  std::optional<Pose2> odometry;  // the odometry reading at `pose`, when the scans carry it
  std::uint64_t scans_processed = 0;
  Trajectory trajectory;
};

void write_checkpoint(const std::filesystem::path& dir, const Checkpoint& checkpoint);
// Throws InputError naming the file when a checkpoint is missing or damaged,
// or belongs to another robot.
Checkpoint read_checkpoint(const std::filesystem::path& dir, const std::string& name);
bool has_checkpoint(const std::filesystem::path& dir);
// A fresh start (no --resume) where an earlier run left a checkpoint: its
// files (checkpoint.json, checkpoint.dsmap, trajectory.tum) move to
// DIR/previous/ (replacing what an older one left there) instead of being
// overwritten. Returns that folder, or nullopt when there was none.
std::optional<std::filesystem::path> set_aside_checkpoint(const std::filesystem::path& dir);

}  // namespace dsswarm::agent
