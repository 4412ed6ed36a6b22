#include "agent/checkpoint.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include <cmath>
#include <fstream>

#include "common/errors.hpp"
#include "io/atomic_file.hpp"
#include "io/maps/dsmap.hpp"

namespace dsswarm::agent {
namespace {

namespace fs = std::filesystem;

fs::path map_file(const fs::path& dir) { return dir / "checkpoint.dsmap"; }
fs::path state_file(const fs::path& dir) { return dir / "checkpoint.json"; }
fs::path trajectory_file(const fs::path& dir) { return dir / "trajectory.tum"; }

Pose2 pose_field(const nlohmann::json& j, const char* field, const fs::path& file) {
  const auto p = j.at(field).get<std::vector<double>>();
  if (p.size() != 3 || !std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
    throw InputError(fmt::format("{}: {} must be three finite numbers", file.string(), field));
  return {p[0], p[1], p[2]};
}

}  // namespace

void write_checkpoint(const fs::path& dir, const Checkpoint& c) {
  fs::create_directories(dir);
  write_dsmap(map_file(dir).string(), c.snapshot);
  write_tum(trajectory_file(dir), c.trajectory);
  nlohmann::json j{{"name", c.name},
                   {"pose", {c.pose.x, c.pose.y, c.pose.theta}},
                   {"stamp", c.stamp},
                   {"scans_processed", c.scans_processed},
                   {"own_version", c.snapshot.layers.empty() ? 0 : c.snapshot.layers.front().version}};
  if (c.odometry) j["odometry"] = {c.odometry->x, c.odometry->y, c.odometry->theta};
  write_file_atomically(state_file(dir), j.dump(2) + "\n");
}

bool has_checkpoint(const fs::path& dir) { return fs::exists(state_file(dir)) && fs::exists(map_file(dir)); }

Checkpoint read_checkpoint(const fs::path& dir, const std::string& name) {
  const fs::path state = state_file(dir);
  if (!has_checkpoint(dir))
    throw InputError(fmt::format("{}: no checkpoint to resume from (checkpoint.json and checkpoint.dsmap)", dir.string()));
  nlohmann::json j;
  try {
    std::ifstream in(state);
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("{}: not a readable checkpoint ({})", state.string(), e.what()));
  }
  Checkpoint c;
  try {
    c.name = j.at("name").get<std::string>();
    c.pose = pose_field(j, "pose", state);
    if (j.contains("odometry")) c.odometry = pose_field(j, "odometry", state);
    c.stamp = j.at("stamp").get<double>();
    c.scans_processed = j.at("scans_processed").get<std::uint64_t>();
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("{}: {}", state.string(), e.what()));
  }
  if (c.name != name)
    throw InputError(fmt::format("{}: the checkpoint is robot '{}', not '{}'", state.string(), c.name, name));
  c.snapshot = read_dsmap(map_file(dir).string());
  if (c.snapshot.sender != name)
    throw InputError(fmt::format("{}: the map is robot '{}''s, not '{}''s", map_file(dir).string(), c.snapshot.sender, name));
  if (fs::exists(trajectory_file(dir))) c.trajectory = read_tum(trajectory_file(dir));
  // Killed between writing the poses and checkpoint.json: the map and the
  // poses are the newer checkpoint's, the state file the older one's. Pose,
  // stamp and count are the last pose's (one pose per scan processed).
  if (c.trajectory.size() > c.scans_processed) {
    spdlog::warn("{}: older than {} (the robot stopped while writing a checkpoint): going on from its last pose",
                 state.string(), trajectory_file(dir).string());
    c.scans_processed = c.trajectory.size();
    c.pose = c.trajectory.back().pose;
    c.stamp = c.trajectory.back().timestamp;
    c.odometry.reset();  // the older pose's reading
  }
  return c;
}

std::optional<fs::path> set_aside_checkpoint(const fs::path& dir) {
  if (!has_checkpoint(dir)) return std::nullopt;
  const fs::path previous = dir / "previous";
  fs::remove_all(previous);
  fs::create_directories(previous);
  for (const fs::path& f : {state_file(dir), map_file(dir), trajectory_file(dir)})
    if (fs::exists(f)) fs::rename(f, previous / f.filename());
  return previous;
}

}  // namespace dsswarm::agent
