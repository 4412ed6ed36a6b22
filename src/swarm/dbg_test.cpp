#include <gtest/gtest.h>
#include <cstdio>
#include "swarm/swarm_agent.hpp"
#include "sim/swarm_sim.hpp"
#include "matching/scan_scorer.hpp"
using namespace dsswarm;
TEST(Dbg, X) {
  SwarmSimConfig sc; sc.seed = 9;
  SimulatedSwarm sw = simulate_swarm(sc);
  SlamConfig cfg;
  SwarmAgent a("robot1", cfg), b("robot3", cfg);
  const int K = 104;
  for (int k = 0; k <= K; ++k) { a.process(sw.runs[0].log.scans[k]); b.process(sw.runs[2].log.scans[k]); }
  Pose2 ga = sw.runs[0].ground_truth[K].second, gb = sw.runs[2].ground_truth[K].second;
  printf("t %.2f A world %.2f %.2f %.2f  B world %.2f %.2f %.2f\n", sw.runs[0].log.scans[K].timestamp, ga.x, ga.y, ga.theta, gb.x, gb.y, gb.theta);
  RelativePoseConfig rc;
  EncounterView va = a.view(rc), vb = b.view(rc);
  auto r = locate_scan(*va.map, vb.points, va.pose.translation(), rc, 3, vb.surroundings);
  Pose2 truth_place = va.pose * between(ga, gb);
  printf("best %.2f %.2f %.2f score %.3f sur %.3f ss %.2f\n", r.best.pose.x, r.best.pose.y, r.best.pose.theta, r.best.score, r.best.surroundings_score, r.best.same_side_ratio);
  if (r.runner_up) printf("runner %.2f %.2f %.2f score %.3f sur %.3f\n", r.runner_up->pose.x, r.runner_up->pose.y, r.runner_up->pose.theta, r.runner_up->score, r.runner_up->surroundings_score);
  printf("truth %.2f %.2f %.2f score %.3f ss %.2f\n", truth_place.x, truth_place.y, truth_place.theta, score_pose(va.map->finest(), vb.points, truth_place), same_side_ratio(va.map->finest(), vb.points, truth_place));
  MonteCarloMatcher m(rc.refine, 5);
  auto mr = m.match(*va.map, vb.points, truth_place);
  printf("refined from truth %.2f %.2f %.2f score %.3f\n", mr.pose.x, mr.pose.y, mr.pose.theta, mr.score);
  printf("A own map scans %zu, B scans %zu; surroundings %zu\n", a.slam().scans_inserted(), b.slam().scans_inserted(), vb.surroundings.size());
  printf("dist between robots %.2f\n", (ga.translation()-gb.translation()).norm());
}
