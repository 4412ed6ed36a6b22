#include "slam/match_verifier.hpp"

#include <gtest/gtest.h>

#include <string>

#include "common/errors.hpp"
#include "slam/recovery.hpp"

namespace dsswarm {
namespace {

MatchQuality quality(double inliers) { return MatchQuality{.known_fraction = 1.0, .inlier_ratio = inliers}; }

TEST(MatchVerifier, RejectsADropBelowTheRunningAverage) {
  MatchVerifier v(VerifyConfig{});
  v.note_accepted(quality(0.9), true);
  EXPECT_FALSE(v.rejects(quality(0.8)));
  EXPECT_TRUE(v.rejects(quality(0.6)));  // below 0.75 × 0.9
}

TEST(MatchVerifier, TheAverageWeightSetsHowFastTheBarFollows) {
  // After one poor match the slow average still expects good ones; a full
  // weight forgets the good ones at once.
  MatchVerifier slow(VerifyConfig{});
  MatchVerifier fast(VerifyConfig{.average_weight = 1.0});
  for (MatchVerifier* v : {&slow, &fast}) {
    v->note_accepted(quality(0.9), true);
    v->note_accepted(quality(0.5), false);
  }
  EXPECT_TRUE(slow.rejects(quality(0.55)));   // bar 0.75 × 0.86
  EXPECT_FALSE(fast.rejects(quality(0.55)));  // bar 0.75 × 0.5
}

TEST(MatchVerifier, ConfigErrorsNameTheField) {
  try {
    VerifyConfig{.average_weight = 0.0}.validate();
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("slam.verify_average_weight"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(VerifyConfig{}.validate());
}

TEST(RecoveryConfig, ConfigErrorsNameTheField) {
  try {
    RecoveryConfig{.sigma_xy_factor = 0.0}.validate();
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("slam.recovery_sigma_xy_factor"), std::string::npos) << e.what();
  }
  EXPECT_THROW(RecoveryConfig{.evaluations_factor = 0}.validate(), ConfigError);
  EXPECT_NO_THROW(RecoveryConfig{}.validate());
}

}  // namespace
}  // namespace dsswarm
