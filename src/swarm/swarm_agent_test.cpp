#include "swarm/swarm_agent.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <numbers>
#include <string_view>

#include "grid/test_cells.hpp"
#include "sim/test_laps.hpp"
#include "swarm/map_merge.hpp"
#include "swarm/test_scenes.hpp"

namespace dsswarm {
namespace {

// Scans along a straight drive in the L-shaped office, odometry exact from the start.
std::vector<LaserScan> drive(const Pose2& from, const Pose2& to, int scans, std::uint64_t seed) {
  const World world = test::l_shaped_office();
  Rng rng(seed);
  std::vector<LaserScan> out;
  for (int k = 0; k < scans; ++k) {
    const Pose2 p = interpolate(from, to, static_cast<double>(k) / (scans - 1));
    LaserScan scan = simulate_scan(world, p, test::full_circle_lidar(), rng);
    scan.timestamp = 0.1 * k;
    scan.odometry = from.inverse() * p;
    out.push_back(std::move(scan));
  }
  return out;
}

// A merge found at scan 20 takes effect `merge_delay` s of log time later:
// the scans between are localized in the map without it, and the merged map
// installed then is what merging at scan 20 would have given, every later
// scan inserted into it where the robot placed it (none lost, none twice).
TEST(SwarmAgent, AMergeTakesEffectTheDelayAfterItsScanLosingNoScanAndCountingNoneTwice) {
  SwarmAgent a("a", SlamConfig{}), b("b", SlamConfig{});
  a.set_merge_delay(1.0);
  const auto scans_a = drive({1.5, 1.5, 0.4}, {3.5, 2.0, 0.1}, 40, 1);
  for (const LaserScan& s : drive({8.5, 2.0, -2.5}, {5.0, 2.5, 2.9}, 20, 2)) b.process(s);
  for (int k = 0; k < 20; ++k) a.process(scans_a[k]);
  const Pose2 b_in_a = Pose2{1.5, 1.5, 0.4}.inverse() * Pose2{8.5, 2.0, -2.5};
  ASSERT_TRUE(a.absorb(b.snapshot(), b_in_a));
  const double view_stamp = scans_a[19].timestamp;
  a.schedule_merge(7, view_stamp);
  MultiResMap expected = compose_working_map(a.slam().own_map(), a.knowledge().layers());
  std::optional<SwarmAgent::Installed> installed;
  int installed_before = -1;
  for (int k = 20; k < 40; ++k) {
    if (!installed && (installed = a.install_due(scans_a[k].timestamp, true))) installed_before = k;
    if (!installed) {  // not yet in use: the map SLAM localizes in is the one without it
      EXPECT_EQ(test::largest_difference(a.slam().own_map().finest(), a.slam().map().finest()), 0.0) << "scan " << k;
    }
    const std::size_t inserted = a.slam().scans_inserted();
    const SlamStep step = a.process(scans_a[k]);
    if (a.slam().scans_inserted() != inserted) expected.insert_scan(step.pose, Pose2{}, scan_to_points(scans_a[k]));
  }
  ASSERT_TRUE(installed);
  EXPECT_EQ(installed->encounters, std::vector<std::uint64_t>{7});
  EXPECT_FALSE(installed->late);
  // The first scan at least 1 s after the view's (0.1 s apart: scan 29 or 30).
  EXPECT_GE(scans_a[static_cast<std::size_t>(installed_before)].timestamp, view_stamp + 1.0);
  EXPECT_LT(scans_a[static_cast<std::size_t>(installed_before) - 1].timestamp, view_stamp + 1.0);
  for (int level = 0; level < expected.levels(); ++level)
    EXPECT_EQ(test::largest_difference(expected.level(level), a.slam().map().level(level)), 0.0) << "level " << level;
  // b's evidence is in the working map, not in the own map a shares.
  EXPECT_GT(test::largest_difference(a.slam().map().finest(), a.slam().own_map().finest()), 0.1);
}

// With loop closure on, an encounter is a constraint between the scan it was
// found at and the other robot's map frame in this robot's own pose graph,
// and the other robot's finished submaps (sent apart in its snapshot) are
// searched for closures like its own: a transform found a degree off at the
// encounter ends up where the two maps overlap all along the ring, and the
// merged map places the other robot's map there.
TEST(SwarmAgent, WithLoopClosureAnEncounterIsAConstraintThatClosuresIntoTheOtherMapStraighten) {
  const SimulatedRun ra = test::lap(0, 1), rb = test::lap(2, 2);
  const Pose2 start_a = ra.ground_truth.front().second;
  const Pose2 b_in_a = between(start_a, rb.ground_truth.front().second);  // each frame is where its robot started
  SwarmAgent b("b", with_loop_closure());
  for (const LaserScan& s : rb.log.scans) b.process(s);
  b.finish();
  const MapSnapshot sent = b.snapshot();
  ASSERT_GT(sent.layers.front().pieces.size(), 4u);  // its finished submaps, apart

  SwarmAgent a("a", with_loop_closure());
  constexpr std::size_t meet = 60;
  Pose2 seen;
  for (std::size_t i = 0; i < ra.log.scans.size(); ++i) {
    const SlamStep step = a.process(ra.log.scans[i]);
    if (i != meet) continue;
    // What the encounter found: B's frame turned by a degree about where A stands.
    const Pose2 here = between(start_a, ra.ground_truth[i].second);
    seen = here * Pose2(0.0, 0.0, std::numbers::pi / 180.0) * between(here, b_in_a);
    a.tie("b", meet, step.pose, seen);
    ASSERT_TRUE(a.merge(sent, seen));
  }
  a.finish();
  // B's trajectory placed in A's frame, against the truth (mean, m).
  const std::vector<Pose2> b_poses = b.slam().trajectory();
  const auto off = [&](const Pose2& frame) {
    double sum = 0.0;
    for (std::size_t i = 0; i < b_poses.size(); ++i) {
      const Pose2 est = frame * b_poses[i], truth = between(start_a, rb.ground_truth[i].second);
      sum += std::hypot(est.x - truth.x, est.y - truth.y);
    }
    return sum / static_cast<double>(b_poses.size());
  };
  const Pose2 placed = a.knowledge().find("b")->origin_in_holder;
  EXPECT_GT(off(seen), 0.15);
  EXPECT_LT(off(placed), 0.5 * off(seen));
  // B's map bends (its own drift): placed at the robots' true relative
  // start it is off by about as much (0.55 m here); the closures fit it best.
  EXPECT_LT(off(placed), off(b_in_a) + 0.03) << "met " << off(seen) << ", placed " << off(placed);
  EXPECT_GT(a.slam().loop_closer().stats().foreign_accepted, 10u);
  // The merged map is B's pieces where the graph put B's frame.
  const MultiResMap want = compose_working_map(a.slam().own_map(), a.knowledge().layers());
  EXPECT_EQ(test::largest_difference(want.finest(), a.slam().map().finest()), 0.0);
}

// A robot tells a peer its closures into the peer's map (MapMoves), each
// where it lies in both maps; the peer weighs them in its own graph, and the
// two robots' estimates of each other's frame agree.
TEST(SwarmAgent, ClosuresIntoAPeersMapTravelAndThePeerWeighsThem) {
  const SimulatedRun ra = test::lap(0, 1), rb = test::lap(2, 2);
  const Pose2 start_a = ra.ground_truth.front().second;
  const Pose2 b_in_a = between(start_a, rb.ground_truth.front().second);
  const Pose2 seen = b_in_a * Pose2(0.1, -0.05, std::numbers::pi / 180.0);  // as an encounter found it
  const auto run_b = [&] {
    auto b = std::make_unique<SwarmAgent>("b", with_loop_closure());
    for (const LaserScan& scan : rb.log.scans) b->process(scan);
    b->finish();
    return b;
  };
  std::unique_ptr<SwarmAgent> first_b = run_b();
  const MapSnapshot from_b = first_b->snapshot();
  SwarmAgent a("a", with_loop_closure());
  constexpr std::size_t meet = 60;
  for (std::size_t i = 0; i < ra.log.scans.size(); ++i) {
    const SlamStep step = a.process(ra.log.scans[i]);
    if (i != meet) continue;
    a.tie("b", meet, step.pose, seen);
    ASSERT_TRUE(a.merge(from_b, seen));
  }
  a.finish();
  const MapMoves told = a.moves("b", {}, 4096);
  ASSERT_GT(told.closures.size(), 10u);
  const std::vector<LoopClosure>& held = a.slam().loop_closer().closures();
  const auto foreign = std::count_if(held.begin(), held.end(), [](const LoopClosure& c) { return c.foreign; });
  EXPECT_EQ(told.closures.size(), static_cast<std::size_t>(foreign));
  EXPECT_EQ(a.moves("b", {}, 5).closures.size(), 5u);
  EXPECT_TRUE(a.moves("c", {}, 4096).closures.empty());  // no map of c held
  // Each lies where a's graph put it: a's node, at a's frame for b ⊕ b's piece ⊕ the pose in it.
  const MapLayer& layer = *a.knowledge().find("b");
  for (const PeerClosure& c : told.closures) {
    const auto piece =
        std::find_if(layer.pieces.begin(), layer.pieces.end(), [&](const MapPiece& p) { return p.id == c.submap; });
    ASSERT_NE(piece, layer.pieces.end()) << c.submap;
    const Pose2 there = layer.origin_in_holder * piece->pose * c.in_cells;
    EXPECT_LT(std::hypot(there.x - c.node.x, there.y - c.node.y), 0.2);
  }

  // b, having met a the same way, weighs them: its estimate of a's frame
  // comes to agree with a's of b's.
  const MapSnapshot from_a = a.snapshot();
  const auto disagreement = [&](bool weighs) {
    const std::unique_ptr<SwarmAgent> b = weighs ? run_b() : std::move(first_b);
    b->tie("a", 0, b->slam().scan_pose(0), seen.inverse());
    EXPECT_TRUE(b->merge(from_a, seen.inverse()));
    if (weighs) b->follow("a", told);
    b->finish();
    const auto counters = b->loop_counters();
    const auto from_others = std::find_if(counters.begin(), counters.end(), [](const auto& c) {
      return std::string_view(c.first) == "closures_from_others";
    });
    EXPECT_EQ(from_others == counters.end() ? ~std::size_t{0} : from_others->second,
              weighs ? told.closures.size() : 0u);
    const Pose2 d = layer.origin_in_holder * b->knowledge().find("a")->origin_in_holder;
    return std::hypot(d.x, d.y) + 10.0 * std::abs(normalize_angle(d.theta));
  };
  const double alone = disagreement(false), weighing = disagreement(true);
  EXPECT_LT(weighing, 0.7 * alone) << "alone " << alone << ", weighing " << weighing;
}

// With loop closure on a robot localizes in its own submaps, so a peer's
// scan is placed in its own map, not in own ⊕ the layers merged (one merged
// a little off would pull the placement its way: docs/loop_closure.md), and
// without the wide surroundings (closures fit the maps over their shared ground),
// but with its unfinished submaps to place it in as well.
TEST(SwarmAgent, WithLoopClosureAPeersScanIsPlacedInTheOwnMapNotInTheMergedOne) {
  const SimulatedRun ra = test::lap(0, 1), rb = test::lap(2, 2);
  const Pose2 start_a = ra.ground_truth.front().second;
  SwarmAgent b("b", with_loop_closure());
  for (std::size_t i = 0; i < 200; ++i) b.process(rb.log.scans[i]);
  SwarmAgent a("a", with_loop_closure());
  constexpr std::size_t meet = 60;
  for (std::size_t i = 0; i <= meet; ++i) a.process(ra.log.scans[i]);
  ASSERT_TRUE(a.merge(b.snapshot(), between(start_a, rb.ground_truth.front().second)));
  ASSERT_GT(test::largest_difference(a.slam().map().finest(), a.slam().own_map().finest()), 0.1);  // b's evidence is merged
  const EncounterConfig config;
  const EncounterView self = a.view(config.locate);
  EXPECT_EQ(self.map, &a.slam().own_map());
  // The wide surroundings go along to settle near misses (the decision
  // then moves no transform by them): a's own obstacles, not b's.
  auto wide_in = [&](const MultiResMap& map) {
    return surroundings_points(map, self.pose, config.locate.merge_surroundings_radius,
                               config.locate.merge_surroundings_points);
  };
  auto same_points = [](const std::vector<ScanPoint>& x, const std::vector<ScanPoint>& y) {
    return std::equal(x.begin(), x.end(), y.begin(), y.end(),
                      [](const ScanPoint& p, const ScanPoint& q) { return p.x == q.x && p.y == q.y; });
  };
  ASSERT_FALSE(self.wide_surroundings.empty());
  EXPECT_TRUE(same_points(self.wide_surroundings, wide_in(a.slam().own_map())));
  EXPECT_FALSE(same_points(self.wide_surroundings, wide_in(a.slam().map())));
  // The unfinished submaps come along (the peer is placed there too): a's
  // own evidence only, the newest of it.
  ASSERT_NE(self.recent_map, nullptr);
  EXPECT_EQ(test::largest_difference(self.recent_map->finest(), a.slam().unfinished_map().finest()), 0.0);
  EncounterConfig whole_only;
  whole_only.locate.place_in_recent_submaps = false;
  EXPECT_EQ(a.view(whole_only.locate).recent_map, nullptr);
  // a's own scan, offered as a peer's would be, lands where a is.
  const Pose2 d = between(self.pose, locate_peer(self, self, config, 7).located.best.pose);
  EXPECT_LT(std::hypot(d.x, d.y), 0.01);

  SlamConfig one_map;
  one_map.loop_closure.enabled = false;
  SwarmAgent plain("p", one_map);  // one map: the robot localizes in own ⊕ foreign, and places peers there
  plain.process(ra.log.scans[0]);
  ASSERT_TRUE(plain.merge(b.snapshot(), Pose2()));
  EXPECT_EQ(plain.view(config.locate).map, &plain.slam().map());
  EXPECT_FALSE(plain.view(config.locate).wide_surroundings.empty());
  EXPECT_EQ(plain.view(config.locate).recent_map, nullptr);
  EXPECT_NE(&plain.slam().map(), &plain.slam().own_map());
}

// After a merge, the robot whose map was merged goes on and closes its loop,
// which moves its submaps and the scan where the two met: told so
// (MapMoves), the holder's copy and the tie follow.
TEST(SwarmAgent, AMapThatLoopClosingMovedAfterTheMergeIsFollowed) {
  // b drives 1.3 laps of a corridor ring on odometry that turns too much,
  // and closes the loop long after it met a.
  const SimulatedRun rb = test::long_loop(1.3, 1), ra = test::lap(0, 1);
  SlamConfig tie_only = with_loop_closure();
  tie_only.loop_closure.foreign_max_pieces = 0;  // the encounter alone places b's frame
  SwarmAgent a("a", tie_only), b("b", with_loop_closure());
  constexpr std::uint64_t kEncounter = 9;
  const std::size_t a_meet = 60, b_meet = rb.log.scans.size() / 3;
  for (std::size_t i = 0; i <= b_meet; ++i) b.process(rb.log.scans[i]);
  for (std::size_t i = 0; i <= a_meet; ++i) a.process(ra.log.scans[i]);
  const Pose2 b_offered = b.slam().pose(), b_in_a(1.0, 2.0, 0.3);
  a.tie("b", a_meet, a.slam().pose(), b_in_a, kEncounter);
  ASSERT_TRUE(a.merge(b.snapshot(), b_in_a));
  ASSERT_FALSE(a.knowledge().find("b")->pieces.empty());
  for (std::size_t i = b_meet + 1; i < rb.log.scans.size(); ++i) b.process(rb.log.scans[i]);
  b.finish();  // closes its loop

  const MapMoves moves = b.moves("a", {{kEncounter, b_meet, b_offered}}, 4096);
  EXPECT_EQ(moves.revision, b.graph_revision());
  ASSERT_EQ(moves.ties.size(), 1u);
  const Pose2 b_now = moves.ties[0].now;
  ASSERT_GT(std::hypot(b_now.x - b_offered.x, b_now.y - b_offered.y), 0.02);  // its scan there moved
  EXPECT_FALSE(a.follow("c", moves));  // no map of c held
  a.finish();
  const Pose2 before = a.knowledge().find("b")->origin_in_holder;
  ASSERT_TRUE(a.follow("b", moves));
  EXPECT_FALSE(a.follow("b", moves));  // nothing more to move
  // a holds b's pieces where b has them now, and its graph places b's frame
  // where the encounter, seen from b's scan as it lies now, puts it.
  std::size_t matched = 0;
  for (const MapPiece& p : a.knowledge().find("b")->pieces)
    for (const PiecePose& q : moves.pieces)
      if (q.id == p.id) {
        EXPECT_EQ(p.pose.x, q.pose.x) << "piece " << p.id;
        ++matched;
      }
  EXPECT_EQ(matched, a.knowledge().find("b")->pieces.size());
  a.finish();
  const Pose2 after = a.knowledge().find("b")->origin_in_holder, want = before * b_offered * b_now.inverse();
  EXPECT_NEAR(after.x, want.x, 1e-4);
  EXPECT_NEAR(after.y, want.y, 1e-4);
  EXPECT_NEAR(normalize_angle(after.theta - want.theta), 0.0, 1e-5);

  SwarmAgent plain("p", SlamConfig{});  // without loop closure nothing moves
  EXPECT_TRUE(plain.moves("b", {{kEncounter, 0, Pose2()}}, 4096).pieces.empty());
  EXPECT_FALSE(plain.follow("b", moves));
}

// A robot resumed from a checkpoint gives its submaps ids after the saved
// ones: its peers still hold those, and a reused id would stand for other
// evidence. Peers' closures into the saved submaps go into the saved map.
TEST(SwarmAgent, AResumedRobotGivesItsSubmapsNewIds) {
  const SimulatedRun rb = test::long_loop(1.3, 1), ra = test::lap(0, 1);
  SwarmAgent b("b", with_loop_closure());
  const std::size_t half = rb.log.scans.size() / 2;
  for (std::size_t i = 0; i < half; ++i) b.process(rb.log.scans[i]);
  const MapSnapshot saved = b.snapshot();
  const MapLayer* saved_own = nullptr;
  for (const MapLayer& l : saved.layers)
    if (l.origin == "b") saved_own = &l;
  ASSERT_NE(saved_own, nullptr);
  ASSERT_GE(saved_own->pieces.size(), 2u);
  std::int32_t next = 0;
  for (const MapPiece& p : saved_own->pieces) next = std::max(next, p.id + 1);

  SwarmAgent resumed("b", with_loop_closure(), saved, b.slam().pose());
  for (std::size_t i = half; i < rb.log.scans.size(); ++i) resumed.process(rb.log.scans[i]);
  resumed.finish();
  const MapSnapshot now = resumed.snapshot();
  std::vector<std::int32_t> ids;
  for (const MapLayer& l : now.layers)
    if (l.origin == "b")
      for (const MapPiece& p : l.pieces) ids.push_back(p.id);
  ASSERT_GE(ids.size(), 2u);  // the saved map as one submap, and new ones
  EXPECT_EQ(*std::min_element(ids.begin(), ids.end()), next);
  for (const PiecePose& p : resumed.moves("a", {}, 4096).pieces) EXPECT_GE(p.id, next);

  SwarmAgent a("a", with_loop_closure());
  for (std::size_t i = 0; i < 60; ++i) a.process(ra.log.scans[i]);
  ASSERT_TRUE(resumed.merge(a.snapshot(), Pose2(1.0, 2.0, 0.3)));
  MapMoves told;
  // Into a saved piece (now in submap 0), two new ones, and one the robot never gave out.
  told.closures = {{next - 1, Pose2(), Pose2()}, {next, Pose2(), Pose2()}, {next + 1, Pose2(), Pose2()},
                   {-1, Pose2(), Pose2()}};
  resumed.follow("a", told);
  EXPECT_EQ(resumed.slam().loop_closer().peer_closures(), 3u);
}

// The frames a checkpoint knew are tied into the resumed robot's new graph
// at its first node, where the checkpoint had them: the closures it is told
// weigh at once, not only after its next encounter.
TEST(SwarmAgent, AResumedRobotTiesTheFramesItKnew) {
  const SimulatedRun rb = test::long_loop(1.3, 1), ra = test::lap(0, 1);
  SwarmAgent a("a", with_loop_closure()), b("b", with_loop_closure());
  for (std::size_t i = 0; i < 60; ++i) a.process(ra.log.scans[i]);
  const std::size_t half = rb.log.scans.size() / 2;
  for (std::size_t i = 0; i < half; ++i) b.process(rb.log.scans[i]);
  const Pose2 a_in_b(1.0, 2.0, 0.3);
  ASSERT_TRUE(b.merge(a.snapshot(), a_in_b));

  SwarmAgent resumed("b", with_loop_closure(), b.snapshot(), b.slam().pose());
  const ForeignMaps& foreign = resumed.slam().loop_closer().foreign();
  ASSERT_EQ(foreign.tied().size(), 1u);
  EXPECT_FALSE(foreign.tied()[0]);
  for (std::size_t i = half; i < half + 20; ++i) resumed.process(rb.log.scans[i]);
  EXPECT_TRUE(foreign.tied()[0]);
  resumed.finish();
  const Pose2 held = resumed.knowledge().find("a")->origin_in_holder;
  EXPECT_NEAR(held.x, a_in_b.x, 0.05);
  EXPECT_NEAR(held.y, a_in_b.y, 0.05);
  EXPECT_NEAR(normalize_angle(held.theta - a_in_b.theta), 0.0, 0.01);
}

}  // namespace
}  // namespace dsswarm
