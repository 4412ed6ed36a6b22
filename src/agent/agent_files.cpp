#include "agent/agent_files.hpp"

#include <algorithm>

#include "agent/outcome_json.hpp"
#include "common/process_usage.hpp"
#include "config/config_json.hpp"
#include "io/atomic_file.hpp"
#include "io/maps/map_server.hpp"
#include "io/maps/render.hpp"

namespace dsswarm::agent {
namespace {

namespace fs = std::filesystem;

nlohmann::json percentiles(std::vector<double> v) {
  if (v.empty()) return nullptr;
  std::sort(v.begin(), v.end());
  return {{"count", v.size()}, {"median", v[v.size() / 2]}, {"max", v.back()}};
}

}  // namespace

nlohmann::json agent_stats(const SwarmAgent& a, const Trajectory& trajectory, const AgentReport& r,
                           const SwarmConfig& config) {
  const protocol::AgentStatus& s = r.status;
  nlohmann::json j;
  j["name"] = a.name();
  j["scans"] = trajectory.size();
  j["scans_received"] = s.scans_received;
  j["scans_processed"] = s.scans_processed;
  j["scans_skipped"] = s.scans_skipped;
  j["scans_in_checkpoint"] = r.scans_in_checkpoint;
  for (const auto& [name, count] : a.slam().scan_counters()) j[name] = count;
  for (const auto& [name, count] : a.loop_counters()) j[name] = count;
  j["wall_seconds"] = r.wall_seconds;
  j["cpu_seconds"] = r.cpu_seconds;
  j["largest_scan_gap_ms"] = r.largest_gap_ms;
  j["largest_scan_gap_during_encounter_ms"] = r.largest_gap_during_encounter_ms;
  j["merge_latency_ms"] = percentiles(r.merge_latencies_ms);
  j["merge_ready_ms"] = percentiles(r.merge_ready_ms);
  j["merges_late"] = r.merges_late;
  j["encounters"] = s.encounters;
  j["encounters_accepted"] = s.encounters_accepted;
  j["messages_rejected"] = r.rejected_by_reason;
  j["moved_received"] = r.moved_received;
  j["moved_bytes_received"] = r.moved_bytes_received;
  j["messages_deferred"] = r.messages_deferred;
  j["proximity_triggers_late"] = r.triggers_late;
  j["knows"] = nlohmann::json::array();
  for (const MapLayer& l : a.knowledge().layers())
    j["knows"].push_back({{"origin", l.origin}, {"version", l.version}, {"hops", l.hops},
                          {"origin_in_holder", {l.origin_in_holder.x, l.origin_in_holder.y, l.origin_in_holder.theta}}});
  j["map_version"] = a.own_version();
  j["map_bytes"] = a.slam().map().memory_bytes() + (a.knowledge().size() > 0 ? a.slam().own_map().memory_bytes() : 0);
  j["peak_rss_bytes"] = peak_rss_bytes();
  j["config"] = to_json(config);
  return j;
}

void write_agent_files(const fs::path& dir, const SwarmAgent& a, const Trajectory& trajectory, const AgentReport& r,
                       const SwarmConfig& config) {
  fs::create_directories(dir);
  write_tum(dir / "trajectory.tum", trajectory);
  {  // one raster at a time: a building's is tens of MB
    const GridRaster own = a.slam().own_map().finest().to_raster();
    if (own.width > 0) write_map_server(dir / "map.yaml", own);
  }
  const GridRaster merged = a.slam().map().finest().to_raster();
  if (merged.width > 0) {
    write_map_server(dir / "merged_map.yaml", merged);
    Image picture = render_map(merged, fitting_scale(merged));
    std::vector<Eigen::Vector2d> path;
    for (const StampedPose& p : trajectory) path.push_back(p.pose.translation());
    draw_polyline(picture, merged, path, agent_colour(0), 1);
    write_png(dir / "merged_map.png", picture);
  }
  nlohmann::json encounters = nlohmann::json::array();
  for (const protocol::EncounterOutcome& o : r.outcomes) encounters.push_back(to_json(o));
  write_file_atomically(dir / "encounters.json",
                        nlohmann::json{{"robot", a.name()}, {"encounters", encounters}}.dump(2) + "\n");
  write_file_atomically(dir / "stats.json", agent_stats(a, trajectory, r, config).dump(2) + "\n");
}

}  // namespace dsswarm::agent
