#include "eval/swarm_truth.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "common/errors.hpp"

namespace dsswarm {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// Two robots that drove straight lines, A from the world origin, B from (5, 2)
// facing backwards; each trajectory in its own frame (its start at identity).
struct Scene {
  SwarmRunResult run;
  SwarmTruth truth;
  Pose2 b_start{5.0, 2.0, std::numbers::pi};
};

Scene scene(double slam_drift_per_step = 0.0) {
  Scene s;
  for (int r = 0; r < 2; ++r) {
    const Pose2 start = r == 0 ? Pose2{} : s.b_start;
    SwarmAgentResult a;
    a.name = std::string(r == 0 ? "a" : "b");
    Trajectory truth;
    for (int k = 0; k < 20; ++k) {
      const Pose2 own{0.1 * k + slam_drift_per_step * k, 0.0, 0.0};
      a.trajectory.push_back({static_cast<double>(k), own});
      truth.push_back({static_cast<double>(k), start * Pose2{0.1 * k, 0.0, 0.0}});
    }
    s.truth.world_poses.push_back(std::move(truth));
    s.run.agents.push_back(std::move(a));
  }
  return s;
}

EncounterRecord met_at(const Scene& s, int k, const Pose2& transform_error = {}) {
  EncounterRecord r;
  r.a = std::string("a");  // (GCC 12 -Wrestrict false positive on assigning literals)
  r.b = std::string("b");
  r.accepted = true;
  r.a_log_time = r.b_log_time = k;
  r.a_pose_in_a = s.run.agents[0].trajectory[static_cast<std::size_t>(k)].pose;
  r.b_pose_in_b = s.run.agents[1].trajectory[static_cast<std::size_t>(k)].pose;
  r.b_frame_in_a = s.b_start * transform_error;
  return r;
}

TEST(SwarmTruth, AnExactTransformScoresZeroUnderEveryReference) {
  const Scene s = scene();
  const EncounterTruthScore e = EncounterScorer(s.run, s.truth).score(met_at(s, 10));
  EXPECT_NEAR(e.true_transform.x, 5.0, 1e-9);
  for (const ErrorPair& p : {e.frame_error, e.aligned_error, e.error, *e.causal_error}) {
    EXPECT_NEAR(p.metres, 0.0, 1e-9);
    EXPECT_NEAR(p.degrees, 0.0, 1e-9);
  }
  EXPECT_FALSE(e.wrong);
}

TEST(SwarmTruth, AnOffsetTransformIsMeasuredAtRobotB) {
  const Scene s = scene();
  // B's frame placed 0.2 m off and turned 1°: at B (1 m from its frame's
  // origin) the rotation adds about 1.7 cm.
  const EncounterTruthScore e = EncounterScorer(s.run, s.truth).score(met_at(s, 10, Pose2{0.2, 0.0, 1.0 * kDeg}));
  EXPECT_NEAR(e.frame_error.degrees, 1.0, 1e-9);
  EXPECT_GT(e.frame_error.metres, 0.2);
  EXPECT_LT(e.frame_error.metres, 0.23);
  EXPECT_FALSE(e.wrong);
  const EncounterTruthScore far = EncounterScorer(s.run, s.truth).score(met_at(s, 10, Pose2{1.0, 0.0, 0.0}));
  EXPECT_TRUE(far.wrong);
}

TEST(SwarmTruth, AtesAndCoverageComeFromTheTrajectoriesAndMaps) {
  Scene s = scene(0.01);  // SLAM overestimates each step by 1 cm
  auto map = std::make_shared<MultiResMap>();
  map->insert_scan(Pose2{}, Pose2{}, {{1.0f, 0.0f, 1.0f}, {0.0f, 1.0f, 1.0f}});
  for (SwarmAgentResult& a : s.run.agents) a.own_map = a.working_map = map;
  const std::vector<AgentTruthScore> scores = score_agents(s.run, s.truth);
  ASSERT_EQ(scores.size(), 2u);
  EXPECT_GT(scores[0].ate_rmse, 0.01);
  EXPECT_LT(scores[0].ate_rmse, 0.2);
  // Each knows its own part only: the two maps sit in different places of the world.
  EXPECT_GT(scores[0].coverage, 0.3);
  EXPECT_LT(scores[0].coverage, 0.7);
  s.truth.world_poses.pop_back();
  EXPECT_THROW(score_agents(s.run, s.truth), ConfigError);
}

}  // namespace
}  // namespace dsswarm
