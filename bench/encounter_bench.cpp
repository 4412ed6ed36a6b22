// One encounter between two robots that each mapped a 100 m × 100 m building
// at 5 cm: what they exchange (bytes) and what matching and merging cost on
// one core. Prints figures; not a test. Usage: build/bench/encounter_bench [side_m]
#include <fmt/core.h>
#include <sys/resource.h>

#include <chrono>
#include <cstdlib>

#include "io/maps/dsmap.hpp"
#include "sim/lidar.hpp"
#include "sim/world.hpp"
#include "swarm/encounter.hpp"
#include "swarm/map_merge.hpp"

namespace {

using namespace dsswarm;
using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

LidarConfig lidar() {
  LidarConfig l;
  l.beams = 720;
  l.fov = 2.0 * std::numbers::pi;
  l.range_max = 30.0;
  return l;
}

// Scans from every free spot of a 2.5 m lattice (a robot that went everywhere),
// in a map frame whose origin is at `frame` in the world.
MultiResMap map_everything(const World& world, const Pose2& frame, Rng& rng, std::vector<Pose2>& poses) {
  MultiResMap map;
  const Box b = world.bounds();
  for (double y = b.min.y() + 1.2; y < b.max.y(); y += 2.5)
    for (double x = b.min.x() + 1.2; x < b.max.x(); x += 2.5) {
      if (!world.is_free({x, y}, 0.4)) continue;
      const Pose2 p{x, y, rng.uniform(-3.14, 3.14)};
      poses.push_back(p);
      map.insert_scan(frame.inverse() * p, Pose2{}, scan_to_points(simulate_scan(world, p, lidar(), rng)));
    }
  return map;
}

std::size_t peak_rss_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<std::size_t>(u.ru_maxrss) / 1024;
}

}  // namespace

int main(int argc, char** argv) {
  const double side = argc > 1 ? std::atof(argv[1]) : 100.0;
  WorldConfig wc;
  wc.width = side;
  wc.height = side;
  wc.rooms_x = static_cast<int>(side / 7.5);
  wc.rooms_y = 2 * static_cast<int>(side / 20.0);
  wc.corridor_width = 2.5;
  validate(wc);
  const World world = generate_world(wc);
  Rng rng(1);
  auto t0 = Clock::now();
  std::vector<Pose2> poses_a, poses_b;
  const Pose2 frame_a{5.0, 5.0, 0.3}, frame_b{side - 5.0, side - 7.0, 2.4};
  const MultiResMap a = map_everything(world, frame_a, rng, poses_a);
  const MultiResMap b = map_everything(world, frame_b, rng, poses_b);
  fmt::print("building {:.0f} m × {:.0f} m; two maps of {} scans each built in {:.1f} s\n", side, side, poses_a.size(),
             ms_since(t0) / 1000.0);
  fmt::print("map: {:.1f} M cells allocated over {} levels, {:.0f} MB in memory\n", static_cast<double>(a.cells_allocated()) / 1e6,
             a.levels(), static_cast<double>(a.memory_bytes()) / 1e6);

  // The exchange: B's snapshot as bytes on the wire, and back.
  const MapSnapshot snapshot{"b", {MapLayer{"b", 1, Pose2{}, 0, std::make_shared<const MultiResMap>(b), {}}}};
  t0 = Clock::now();
  const std::vector<std::uint8_t> wire = encode_dsmap(snapshot);
  const double encode_ms = ms_since(t0);
  t0 = Clock::now();
  const MapSnapshot received = decode_dsmap(wire, "bench");
  const double decode_ms = ms_since(t0);
  fmt::print("snapshot: {:.2f} MB on the wire ({:.2f} bytes per allocated cell), encode {:.0f} ms, decode {:.0f} ms\n",
             static_cast<double>(wire.size()) / 1e6, static_cast<double>(wire.size()) / static_cast<double>(b.cells_allocated()),
             encode_ms, decode_ms);

  // Both robots in the middle of the building, 2 m apart, facing anywhere.
  Pose2 a_world, b_world;
  for (const Pose2& p : poses_a)
    if ((p.translation() - Eigen::Vector2d(side / 2, side / 2)).norm() < 10.0 &&
        world.is_free(p.translation() + Eigen::Vector2d(1.5, 1.0), 0.4) &&
        world.is_segment_free(p.translation(), p.translation() + Eigen::Vector2d(1.5, 1.0), 0.05)) {
      a_world = p;
      b_world = {p.x + 1.5, p.y + 1.0, p.theta + 2.0};
      break;
    }
  RelativePoseConfig rc;
  EncounterView va{&a, scan_to_points(simulate_scan(world, a_world, lidar(), rng)), frame_a.inverse() * a_world, {},
                   {}};
  EncounterView vb{received.layers[0].map.get(), scan_to_points(simulate_scan(world, b_world, lidar(), rng)),
                   frame_b.inverse() * b_world, {}, {}};
  va.surroundings = surroundings_points(a, va.pose, rc.surroundings_radius, rc.surroundings_points);
  vb.surroundings = surroundings_points(b, vb.pose, rc.surroundings_radius, rc.surroundings_points);
  va.wide_surroundings = surroundings_points(a, va.pose, rc.merge_surroundings_radius, rc.merge_surroundings_points);
  vb.wide_surroundings = surroundings_points(b, vb.pose, rc.merge_surroundings_radius, rc.merge_surroundings_points);
  t0 = Clock::now();
  const EncounterEstimate e = estimate_encounter(va, vb, EncounterConfig{}, 7);
  const double match_ms = ms_since(t0);
  const Pose2 truth = frame_a.inverse() * frame_b;
  const Pose2 d = between(truth * vb.pose, e.b_frame_in_a * vb.pose);
  fmt::print("match (both directions + verification): {:.0f} ms, {}; error at B {:.3f} m / {:.2f}°\n", match_ms,
             e.accepted ? "accepted" : "rejected: " + e.reason, std::hypot(d.x, d.y),
             std::abs(normalize_angle(d.theta)) * 180.0 / std::numbers::pi);
  t0 = Clock::now();
  MultiResMap merged = a;
  combine_into(merged, *received.layers[0].map, e.accepted ? e.b_frame_in_a : truth);
  fmt::print("merge (resample B's 3 levels into A's frame, Dempster per cell): {:.0f} ms\n", ms_since(t0));
  fmt::print("peak RSS {} MB\n", peak_rss_mb());
  return 0;
}
