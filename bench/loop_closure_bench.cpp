// Loop closing on simulated runs with exact ground truth: for each seed, the
// ATE of local SLAM alone (its own frame) and after loop closing, and every
// accepted loop closure checked against the truth: its pose relative to the
// submap's node nearest to it, against the true relative pose of the two
// scans (false beyond 0.2 m or 2 degrees). Prints one line per seed and a
// summary with the searches' outcomes; not a test.
// Usage: build/bench/loop_closure_bench [first_seed] [last_seed] [scene: loop|building] [lidar range, m]
//        [config.json]
// (default range 8 m: a room or a stretch of corridor at a time; the
// configuration's SLAM sections on top of the defaults with loop closure on).
#include <fmt/core.h>

#include <cstdlib>
#include <algorithm>
#include <exception>
#include <numbers>
#include <string>

#include "config/config_json.hpp"
#include "eval/ate.hpp"
#include "sim/loop_world.hpp"
#include "sim/scenario.hpp"
#include "slam/slam.hpp"

namespace {

using namespace dsswarm;

constexpr double kFalseXy = 0.2;                            // m
constexpr double kFalseTheta = 2.0 * std::numbers::pi / 180.0;  // rad
constexpr std::size_t kShapeScans = 60;  // a false closure's submap judged over this many scans each side

SimulatedRun simulate(const std::string& scene, std::uint64_t seed, double range) {
  if (scene == "building") {
    DemoConfig demo;
    demo.world.seed = seed;
    demo.seed = seed;
    demo.lidar.range_max = range;
    return simulate_demo(demo);
  }
  LoopWorldConfig config;
  config.seed = seed;
  const LoopWorld w = make_loop_world(config);
  LidarConfig lidar;
  lidar.range_max = range;
  lidar.noise_std = 0.02;
  RobotConfig robot;
  robot.odom_drift = 0.02;
  return simulate_run(w.world, w.tour, w.start, robot, lidar, seed);
}

Trajectory stamped(const SimulatedRun& run, const std::vector<Pose2>& poses) {
  Trajectory t;
  for (std::size_t i = 0; i < poses.size(); ++i) t.push_back({run.log.scans[i].timestamp, poses[i]});
  return t;
}

// One closure judged false, with how far local SLAM's own poses around the
// submap node it was checked against are from the truth: when they are far
// off, the submap itself is out of shape and the verdict is not a clean one.
void print_false(const SimulatedRun& run, const std::vector<Pose2>& local, const LoopClosure& c, double error_xy,
                 double error_theta) {
  const std::size_t n = *c.nearest_scan;
  double submap_error = 0.0;
  for (std::size_t j = n > kShapeScans ? n - kShapeScans : 0; j < std::min(local.size(), n + kShapeScans); ++j) {
    const Pose2 truth = between(run.ground_truth[n].second, run.ground_truth[j].second);
    const Pose2 d = between(truth, between(local[n], local[j]));
    submap_error = std::max(submap_error, std::hypot(d.x, d.y));
  }
  fmt::print("  false: scan {} (t {:.1f} s) against scan {} (t {:.1f} s): {:.3f} m / {:.2f} deg off; local SLAM within "
             "{} scans of scan {}: up to {:.3f} m off the truth\n",
             c.scan, run.log.scans[c.scan].timestamp, n, run.log.scans[n].timestamp, error_xy,
             error_theta * 180.0 / std::numbers::pi, kShapeScans, n, submap_error);
}

int run(int argc, char** argv) {
  const int first = argc > 1 ? std::atoi(argv[1]) : 1, last = argc > 2 ? std::atoi(argv[2]) : 10;
  const std::string scene = argc > 3 ? argv[3] : "loop";
  const double range = argc > 4 ? std::atof(argv[4]) : 8.0;
  SlamConfig base = with_loop_closure();
  if (argc > 5) load_slam_config(argv[5], base);
  std::size_t accepted = 0, wrong = 0;
  LoopClosureStats all;
  double worst_ate = 0.0, worst_closure = 0.0;
  for (int seed = first; seed <= last; ++seed) {
    const SimulatedRun run = simulate(scene, static_cast<std::uint64_t>(seed), range);
    Trajectory truth;
    for (const auto& [t, p] : run.ground_truth) truth.push_back({t, p});
    SlamConfig config = base;
    config.seed = static_cast<std::uint64_t>(seed);
    Slam slam(config);
    for (const LaserScan& s : run.log.scans) slam.process(s);
    slam.finish();
    const double local = evaluate_ate(stamped(run, slam.local_trajectory()), truth).rmse;
    const double closed = evaluate_ate(stamped(run, slam.trajectory()), truth).rmse;
    std::size_t bad = 0;
    double largest = 0.0;
    for (const LoopClosure& c : slam.loop_closer().closures()) {
      if (!c.nearest_scan) continue;
      const Pose2 truth_relative = between(run.ground_truth[*c.nearest_scan].second, run.ground_truth[c.scan].second);
      const Pose2 e = between(truth_relative, c.relative_to_nearest);
      largest = std::max(largest, std::hypot(e.x, e.y));
      if (std::hypot(e.x, e.y) > kFalseXy || std::abs(e.theta) > kFalseTheta) {
        ++bad;
        print_false(run, slam.local_trajectory(), c, std::hypot(e.x, e.y), e.theta);
      }
    }
    const LoopClosureStats& st = slam.loop_closer().stats();
    fmt::print("{} seed {:3d}: {:5d} scans, ATE local {:.3f} m, closed {:.3f} m; closures {} accepted of {} searches "
               "({} candidates), {} false, largest error {:.3f} m\n",
               scene, seed, run.log.scans.size(), local, closed, st.accepted, st.searches, st.candidates, bad, largest);
    accepted += st.accepted;
    add_stats(all, st);
    wrong += bad;
    worst_ate = std::max(worst_ate, closed);
    worst_closure = std::max(worst_closure, largest);
  }
  fmt::print("{} seeds {}-{} ({} m lidar): {} closures accepted of {} searches, {} false; worst ATE {:.3f} m, worst "
             "closure error {:.3f} m\n",
             scene, first, last, range, accepted, all.searches, wrong, worst_ate, worst_closure);
  fmt::print("searches: {} verified; rejected: no match {}, unknown {}, inliers {}, same side {}, ambiguous {}, prior "
             "fits {}; of the verified, inconsistent {}, residual {}\n",
             all.candidates, all.rejected_no_match, all.rejected_unknown, all.rejected_inliers, all.rejected_same_side,
             all.rejected_ambiguous, all.rejected_prior_fits, all.rejected_inconsistent, all.rejected_residual);
  return 0;
}

}  // namespace

// A bad argument or configuration (e.g. a lidar range of 0) is reported, not thrown out of main.
int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    fmt::print(stderr, "loop_closure_bench: {}\nusage: loop_closure_bench [first_seed] [last_seed] [loop|building] "
                       "[lidar range, m] [config.json]\n", e.what());
    return 2;
  }
}
