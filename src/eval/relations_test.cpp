#include "eval/relations.hpp"

#include <gtest/gtest.h>

#include "common/test_files.hpp"

#include <algorithm>
#include <fstream>
#include <numbers>
#include <random>
#include <sstream>
#include <string>

#include "common/errors.hpp"
#include "eval/metrics_json.hpp"
#include "eval/trajectory_lookup.hpp"

namespace dsswarm {
namespace {

using test::fresh_dir;
using test::write_text;

namespace fs = std::filesystem;
constexpr double kPi = std::numbers::pi;

template <typename F>
std::string input_error_message(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected InputError";
  return {};
}

// A winding ground-truth path with timestamps 0, 0.1, 0.2, ...
Trajectory make_truth(std::size_t n) {
  Trajectory t;
  Pose2 p(2.0, -1.0, 0.4);
  for (std::size_t i = 0; i < n; ++i) {
    t.push_back({0.1 * static_cast<double>(i), p});
    p = p * Pose2(0.3, 0.02 * std::sin(static_cast<double>(i)), 0.15 * std::cos(0.3 * static_cast<double>(i)));
  }
  return t;
}

// Relations between consecutive poses and some long-range pairs, from the truth.
std::vector<Relation> make_relations(const Trajectory& truth) {
  std::vector<Relation> rel;
  for (std::size_t i = 0; i + 1 < truth.size(); ++i) {
    rel.push_back({truth[i].timestamp, truth[i + 1].timestamp, between(truth[i].pose, truth[i + 1].pose)});
  }
  for (std::size_t i = 0; i + 17 < truth.size(); i += 5) {
    rel.push_back({truth[i + 17].timestamp, truth[i].timestamp, between(truth[i + 17].pose, truth[i].pose)});
  }
  return rel;
}

// ---------- reading ----------

TEST(ReadRelations, ParsesWithAndWithoutFloatKeyword) {
  const fs::path file = write_text(fresh_dir("rel_parse") / "a.relations",
                                   "# comment\n"
                                   "FLOAT 10.5 11.25 0.4 -0.1 0 0 0 -0.07\n"
                                   "\n"
                                   "976052905.167303 976052911.885496 -0.056990 -0.128430 0.000000  0.0 0.0 -1.682210\r\n");
  const auto rel = read_relations(file);
  ASSERT_EQ(rel.size(), 2u);
  EXPECT_DOUBLE_EQ(rel[0].t1, 10.5);
  EXPECT_DOUBLE_EQ(rel[0].t2, 11.25);
  EXPECT_DOUBLE_EQ(rel[0].motion.x, 0.4);
  EXPECT_DOUBLE_EQ(rel[0].motion.y, -0.1);
  EXPECT_DOUBLE_EQ(rel[0].motion.theta, -0.07);
  EXPECT_DOUBLE_EQ(rel[1].t1, 976052905.167303);
  EXPECT_DOUBLE_EQ(rel[1].motion.theta, -1.682210);
}

TEST(ReadRelations, MalformedLinesNameFileLineAndField) {
  const fs::path dir = fresh_dir("rel_bad");
  std::string msg = input_error_message(
      [&] { read_relations(write_text(dir / "short.relations", "1 2 0 0 0 0 0 0\n1 2 0 0 0 0 0\n")); });
  EXPECT_NE(msg.find("short.relations:2"), std::string::npos) << msg;
  EXPECT_NE(msg.find("expected 8"), std::string::npos) << msg;

  msg = input_error_message(
      [&] { read_relations(write_text(dir / "word.relations", "FLOAT 1 2 0 0 0 0 0 x0.5\n")); });
  EXPECT_NE(msg.find("word.relations:1"), std::string::npos) << msg;
  EXPECT_NE(msg.find("'yaw'"), std::string::npos) << msg;

  msg = input_error_message([&] { read_relations(write_text(dir / "empty.relations", "# nothing\n\n")); });
  EXPECT_NE(msg.find("no relations"), std::string::npos) << msg;

  msg = input_error_message([&] { read_relations(dir / "absent.relations"); });
  EXPECT_NE(msg.find("absent.relations"), std::string::npos) << msg;
}

TEST(ReadRelationsRealData, BenchmarkFiles) {
  const fs::path dir = fs::path(DSSWARM_SHARED_DATA) / "relations";
  if (!fs::is_directory(dir)) GTEST_SKIP() << "real data not found at " << dir;
  const std::pair<const char*, std::size_t> expected[] = {{"intel", 2984}, {"fr079", 1685}, {"mit-csail", 1172}};
  for (const auto& [name, count] : expected) {
    SCOPED_TRACE(name);
    const auto rel = read_relations(dir / (std::string(name) + ".relations"));
    EXPECT_EQ(rel.size(), count);
    for (const Relation& r : rel) {
      ASSERT_GT(r.t1, 0.0);
      ASSERT_GT(r.t2, 0.0);
      ASSERT_LE(std::abs(r.motion.theta), kPi);
      ASSERT_LT(std::hypot(r.motion.x, r.motion.y), 100.0);  // indoor buildings
    }
  }
}

// ---------- timestamp lookup ----------

TEST(TimestampIndex, NearestWithinToleranceInUnsortedTrajectory) {
  const Trajectory t = {{5.0, {}}, {1.0, {}}, {3.0, {}}, {3.0000004, {}}, {2.0, {}}};
  const TimestampIndex index(t, "test");
  EXPECT_EQ(index.nearest(1.0004, 0.001), std::optional<std::size_t>(1));
  EXPECT_EQ(index.nearest(4.9995, 0.001), std::optional<std::size_t>(0));
  EXPECT_EQ(index.nearest(3.0000003, 0.001), std::optional<std::size_t>(3));  // nearer of two close entries
  EXPECT_EQ(index.nearest(2.9999, 0.001), std::optional<std::size_t>(2));
  EXPECT_FALSE(index.nearest(2.5, 0.001).has_value());
  EXPECT_FALSE(index.nearest(0.0, 0.5).has_value());
  EXPECT_FALSE(index.nearest(std::numeric_limits<double>::quiet_NaN(), 1.0).has_value());
  EXPECT_DOUBLE_EQ(index.earliest(), 1.0);
  EXPECT_DOUBLE_EQ(index.latest(), 5.0);
}

TEST(TimestampIndex, EqualTimestampsResolveToFileOrder) {
  const Trajectory t = {{2.0, {}}, {1.0, {}}, {1.0, {}}};
  const TimestampIndex index(t, "test");
  EXPECT_EQ(index.nearest(1.0, 0.0), std::optional<std::size_t>(1));
  EXPECT_EQ(index.nearest(1.1, 0.5), std::optional<std::size_t>(1));
}

// ---------- metric ----------

TEST(EvaluateRelations, PerfectTrajectoryHasZeroError) {
  const Trajectory truth = make_truth(60);
  const auto rel = make_relations(truth);
  const RelationMetrics m = evaluate_relations(truth, rel);
  EXPECT_EQ(m.used, rel.size());
  EXPECT_EQ(m.missing, 0u);
  ASSERT_EQ(m.trans_errors.size(), rel.size());
  EXPECT_NEAR(m.trans_mean, 0.0, 1e-12);
  EXPECT_NEAR(m.trans_std, 0.0, 1e-12);
  EXPECT_NEAR(m.rot_mean_deg, 0.0, 1e-10);
  EXPECT_NEAR(m.rot_std_deg, 0.0, 1e-10);
}

TEST(EvaluateRelations, IndependentOfGlobalFrameAndFileOrder) {
  const Trajectory truth = make_truth(60);
  const auto rel = make_relations(truth);
  // The same trajectory in another map frame, shuffled: still perfect.
  Trajectory moved = truth;
  const Pose2 frame(-30.0, 12.0, 2.5);
  for (auto& s : moved) s.pose = frame * s.pose;
  std::mt19937 rng(7);
  std::shuffle(moved.begin(), moved.end(), rng);
  const RelationMetrics m = evaluate_relations(moved, rel);
  EXPECT_EQ(m.used, rel.size());
  EXPECT_NEAR(m.trans_mean, 0.0, 1e-9);
  EXPECT_NEAR(m.rot_mean_deg, 0.0, 1e-8);
}

TEST(EvaluateRelations, ConstantHeadingBiasGivesHandComputedError) {
  // Every estimated pose is turned by phi about its own origin. For a true
  // motion of d straight ahead, the estimate sees it rotated by -phi:
  // δ̂ = (d cos phi, -d sin phi, 0), so ‖δ̂ ⊖ δ‖ = 2 d sin(phi / 2) and the
  // rotational error is 0.
  const double d = 1.0, phi = 0.1;
  Trajectory truth, estimate;
  Pose2 p(5.0, 5.0, 1.0);
  for (int i = 0; i < 10; ++i) {
    truth.push_back({static_cast<double>(i), p});
    estimate.push_back({static_cast<double>(i), p * Pose2(0.0, 0.0, phi)});
    p = p * Pose2(d, 0.0, 0.0);
  }
  const auto rel = make_relations(truth);  // consecutive pairs only for 10 poses
  ASSERT_EQ(rel.size(), 9u);
  const RelationMetrics m = evaluate_relations(estimate, rel);
  const double expected = 2.0 * d * std::sin(phi / 2.0);  // 0.0999583...
  EXPECT_NEAR(m.trans_mean, expected, 1e-12);
  EXPECT_NEAR(m.trans_std, 0.0, 1e-12);
  EXPECT_NEAR(m.rot_mean_deg, 0.0, 1e-10);
}

TEST(EvaluateRelations, MeanAndPopulationStd) {
  // Two relations with translational errors 1 and 3 (mean 2, population std 1)
  // and rotational errors 10° and 30° (mean 20°, std 10°).
  const Trajectory est = {{0.0, Pose2(0, 0, 0)}, {1.0, Pose2(1, 0, 0)}, {2.0, Pose2(1, 0, 0)}};
  const std::vector<Relation> rel = {
      {0.0, 1.0, Pose2(0.0, 0.0, -10.0 * kPi / 180.0)},  // δ⁻¹ ⊕ δ̂ = (cos10°, sin10°, 10°): norm 1
      {1.0, 2.0, Pose2(-3.0, 0.0, 30.0 * kPi / 180.0)},  // estimated motion is identity: error ‖(3,0)‖
  };
  const RelationMetrics m = evaluate_relations(est, rel);
  ASSERT_EQ(m.used, 2u);
  EXPECT_NEAR(m.trans_errors[0], 1.0, 1e-12);
  EXPECT_NEAR(m.trans_errors[1], 3.0, 1e-12);
  EXPECT_NEAR(m.trans_mean, 2.0, 1e-12);
  EXPECT_NEAR(m.trans_std, 1.0, 1e-12);
  EXPECT_NEAR(m.rot_mean_deg, 20.0, 1e-9);
  EXPECT_NEAR(m.rot_std_deg, 10.0, 1e-9);
}

TEST(EvaluateRelations, RotationalErrorWrapsAroundPi) {
  // Estimated turn of +179°, true turn of -179°: the error is 2°, not 358°.
  const Trajectory est = {{0.0, Pose2(0, 0, 0)}, {1.0, Pose2(0, 0, 179.0 * kPi / 180.0)}};
  const RelationMetrics m = evaluate_relations(est, {{0.0, 1.0, Pose2(0, 0, -179.0 * kPi / 180.0)}});
  EXPECT_NEAR(m.rot_mean_deg, 2.0, 1e-9);
}

TEST(EvaluateRelations, MissingTimestampsAreCountedNotScored) {
  const Trajectory truth = make_truth(30);
  const auto rel = make_relations(truth);
  Trajectory est;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    if (i == 10) continue;  // dropped pose: relations 9->10 and 10->11 lose an end
    StampedPose s = truth[i];
    if (i == 20) s.timestamp += 0.002;  // beyond 1 ms: relations 19->20 and 20->21 go missing
    if (i == 5) s.timestamp += 0.0008;  // within 1 ms: still matched
    est.push_back(s);
  }
  const RelationMetrics m = evaluate_relations(est, rel);
  // Poses 10 and 20 have timestamps 1.0 and 2.0. Of the long-range pairs
  // (i+17, i) for i = 0, 5, 10, the last touches pose 10.
  const auto unmatched = [](double t) { return std::abs(t - 1.0) < 1e-9 || std::abs(t - 2.0) < 1e-9; };
  std::size_t expected_missing = 0;
  for (const Relation& r : rel) {
    if (unmatched(r.t1) || unmatched(r.t2)) ++expected_missing;
  }
  EXPECT_EQ(expected_missing, 5u);
  EXPECT_EQ(m.missing, expected_missing);
  EXPECT_EQ(m.used, rel.size() - expected_missing);
  EXPECT_NEAR(m.trans_mean, 0.0, 1e-12);
  // A looser tolerance recovers the shifted pose.
  EXPECT_EQ(evaluate_relations(est, rel, 0.005).missing, 3u);
}

TEST(EvaluateRelations, NothingMatchedIsAnInputErrorWithSpans) {
  const Trajectory truth = make_truth(10);
  Trajectory shifted = truth;
  for (auto& s : shifted) s.timestamp += 1000.0;
  const std::string msg = input_error_message([&] { evaluate_relations(shifted, make_relations(truth)); });
  EXPECT_NE(msg.find("none of the 9 relations"), std::string::npos) << msg;
  EXPECT_NE(msg.find("1000.000000"), std::string::npos) << msg;
  EXPECT_THROW(evaluate_relations({}, make_relations(truth)), InputError);
}

TEST(EvaluateRelations, InvalidToleranceIsConfigError) {
  const Trajectory truth = make_truth(5);
  EXPECT_THROW(evaluate_relations(truth, make_relations(truth), -0.1), ConfigError);
  EXPECT_THROW(evaluate_relations(truth, make_relations(truth), std::numeric_limits<double>::infinity()),
               ConfigError);
}

TEST(EvaluateRelations, JsonHasExactlyTheDocumentedKeys) {
  RelationMetrics m;
  m.trans_mean = 0.5;
  m.trans_std = 0.25;
  m.rot_mean_deg = 3.0;
  m.rot_std_deg = 1.5;
  m.used = 7;
  m.missing = 2;
  m.trans_errors = {1.0};
  const nlohmann::json j = to_json(m);
  EXPECT_EQ(j.size(), 6u);
  EXPECT_EQ(j.at("trans_mean").get<double>(), 0.5);
  EXPECT_EQ(j.at("trans_std").get<double>(), 0.25);
  EXPECT_EQ(j.at("rot_mean_deg").get<double>(), 3.0);
  EXPECT_EQ(j.at("rot_std_deg").get<double>(), 1.5);
  EXPECT_EQ(j.at("used").get<std::size_t>(), 7u);
  EXPECT_EQ(j.at("missing").get<std::size_t>(), 2u);
}

TEST(ReadRelations, ReadsFromAStreamNamingItsSource) {
  std::istringstream good("FLOAT 10.5 11.25 0.4 -0.1 0 0 0 -0.07\n");
  const auto rel = read_relations(good, "memory");
  ASSERT_EQ(rel.size(), 1u);
  EXPECT_DOUBLE_EQ(rel[0].motion.theta, -0.07);
  std::istringstream bad("# comment\n1 2 0 0 0 0 0 nan\n");
  std::string msg = input_error_message([&] { read_relations(bad, "memory"); });
  EXPECT_NE(msg.find("memory:2"), std::string::npos) << msg;
  std::istringstream empty("");
  msg = input_error_message([&] { read_relations(empty, "memory"); });
  EXPECT_EQ(msg, "memory: no relations found");
}

}  // namespace
}  // namespace dsswarm
