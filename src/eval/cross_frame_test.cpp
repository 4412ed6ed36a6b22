#include "eval/cross_frame.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "common/errors.hpp"

namespace dsswarm {
namespace {

// The true path: a quarter circle of radius 10 m, 1 s per step, heading along it.
Pose2 truth(double t) {
  const double a = 0.05 * t;
  return {10.0 * std::sin(a), 10.0 * (1.0 - std::cos(a)), a};
}

// X covers t = 0..14 in the world frame; Y covers t = 16..30 in its own frame,
// `frame` being where Y's frame lies in X's (the world). Relations link each of
// X's poses to Y's 16 s later, stated either way round.
struct Fixture {
  Trajectory x, y;
  std::vector<Relation> relations;
};

Fixture make(const Pose2& frame, double y_bend = 0.0) {
  Fixture f;
  for (int i = 0; i <= 14; ++i) f.x.push_back({double(i), truth(i)});
  for (int i = 16; i <= 30; ++i) {
    // A bend: Y's map drifts sideways with distance from its first pose.
    const Pose2 bent = Pose2(0.0, y_bend * (i - 16), 0.0) * truth(i);
    f.y.push_back({double(i), frame.inverse() * bent});
  }
  for (int i = 0; i <= 14; ++i) {
    const double t1 = i, t2 = i + 16.0;
    if (i % 2 == 0) {
      f.relations.push_back({t1, t2, between(truth(t1), truth(t2))});
    } else {
      f.relations.push_back({t2, t1, between(truth(t2), truth(t1))});
    }
  }
  return f;
}

TEST(CrossFrame, FindsWhereTheOtherTrajectorysFrameLies) {
  const Pose2 frame(3.0, -2.0, 0.7);
  const Fixture f = make(frame);
  const std::optional<Pose2> fit = fit_cross_frame(f.x, f.y, f.relations, 0.001);
  ASSERT_TRUE(fit);
  EXPECT_NEAR(fit->x, frame.x, 1e-9);
  EXPECT_NEAR(fit->y, frame.y, 1e-9);
  EXPECT_NEAR(fit->theta, frame.theta, 1e-9);
}

TEST(CrossFrame, ABentTrajectoryLeavesAnErrorNoFrameRemoves) {
  const Pose2 frame(-1.0, 4.0, -2.0);
  const Fixture f = make(frame, 0.01);
  const std::optional<Pose2> fit = fit_cross_frame(f.x, f.y, f.relations, 0.001);
  ASSERT_TRUE(fit);
  Trajectory joint = f.x;
  for (StampedPose p : f.y) joint.push_back({p.timestamp, *fit * p.pose});
  const RelationMetrics best = evaluate_relations(joint, f.relations, 0.001);
  // Y's poses run 0..0.14 m off sideways: the best frame halves that, no more.
  EXPECT_GT(best.trans_mean, 0.02);
  EXPECT_LT(best.trans_mean, 0.07);
  // Any other frame does worse, e.g. the true one.
  Trajectory at_truth = f.x;
  for (StampedPose p : f.y) at_truth.push_back({p.timestamp, frame * p.pose});
  EXPECT_LT(best.trans_mean, evaluate_relations(at_truth, f.relations, 0.001).trans_mean);
}

TEST(CrossFrame, NeedsTwoRelationsWithOneEndOnEach) {
  Fixture f = make(Pose2{});
  f.relations.resize(1);
  EXPECT_FALSE(fit_cross_frame(f.x, f.y, f.relations, 0.001));
  f.relations.push_back({0.0, 1.0, Pose2(1.0, 0.0, 0.0)});  // both ends on X
  EXPECT_FALSE(fit_cross_frame(f.x, f.y, f.relations, 0.001));
  EXPECT_THROW(fit_cross_frame(f.x, f.y, f.relations, -1.0), ConfigError);
}

}  // namespace
}  // namespace dsswarm
