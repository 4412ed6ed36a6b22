#include "grid/ds_mass.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "grid/evidence_model.hpp"

namespace dsswarm {
namespace {

void expect_mass_near(const DsMass& a, const DsMass& b, float tol = 1e-6f) {
  EXPECT_NEAR(a.occupied, b.occupied, tol);
  EXPECT_NEAR(a.free, b.free, tol);
}

const std::vector<DsMass> kSamples = {{0.0f, 0.0f}, {0.3f, 0.1f}, {0.6f, 0.0f}, {0.0f, 0.7f},
                                      {0.25f, 0.25f}, {0.9f, 0.05f}, {0.05f, 0.9f}};

TEST(DsMass, HandComputedCombination) {
  // o1=.6 f1=.2 u1=.2; o2=.5 f2=.1 u2=.4; K = .6*.1 + .2*.5 = .16
  const DsMass r = combine({0.6f, 0.2f}, {0.5f, 0.1f});
  EXPECT_NEAR(r.occupied, (0.6 * 0.5 + 0.6 * 0.4 + 0.2 * 0.5) / 0.84, 1e-6);
  EXPECT_NEAR(r.free, (0.2 * 0.1 + 0.2 * 0.4 + 0.2 * 0.1) / 0.84, 1e-6);
  EXPECT_NEAR(r.occupied + r.free + r.unknown(), 1.0f, 1e-6);
}

TEST(DsMass, Commutative) {
  for (const auto& a : kSamples)
    for (const auto& b : kSamples) expect_mass_near(combine(a, b), combine(b, a));
}

TEST(DsMass, Associative) {
  for (const auto& a : kSamples)
    for (const auto& b : kSamples)
      for (const auto& c : kSamples) expect_mass_near(combine(combine(a, b), c), combine(a, combine(b, c)), 1e-5f);
}

TEST(DsMass, UnknownIsIdentity) {
  for (const auto& a : kSamples) {
    expect_mass_near(combine(a, DsMass::vacuous()), a);
    expect_mass_near(combine(DsMass::vacuous(), a), a);
  }
}

TEST(DsMass, AgreeingEvidenceStrengthens) {
  const DsMass r = combine({0.4f, 0.0f}, {0.4f, 0.0f});
  EXPECT_NEAR(r.occupied, 1.0f - 0.6f * 0.6f, 1e-6);
}

TEST(DsMass, ConflictIsRenormalisedAway) {
  // Certain-ish occupied meets some free evidence: conflict K = .8*.5 removed.
  const DsMass r = combine({0.8f, 0.0f}, {0.0f, 0.5f});
  EXPECT_NEAR(r.occupied, 0.8 * 0.5 / 0.6, 1e-6);
  EXPECT_NEAR(r.free, 0.2 * 0.5 / 0.6, 1e-6);
}

TEST(DsMass, FullConflictGivesVacuousNotNaN) {
  const DsMass r = combine({1.0f, 0.0f}, {0.0f, 1.0f});
  EXPECT_FALSE(std::isnan(r.occupied));
  expect_mass_near(r, DsMass::vacuous());
}

TEST(DsMass, OccupancyCountsUnknownAsHalf) {
  EXPECT_FLOAT_EQ(DsMass::vacuous().occupancy(), 0.5f);
  EXPECT_FLOAT_EQ((DsMass{1.0f, 0.0f}).occupancy(), 1.0f);
  EXPECT_FLOAT_EQ((DsMass{0.0f, 1.0f}).occupancy(), 0.0f);
}

TEST(EvidenceModel, KeepsMinimumUnknownSoCellsCanBeRevised) {
  const EvidenceModel ev;
  DsMass cell;
  for (int i = 0; i < 500; ++i) cell = ev.update(cell, ev.hit());
  EXPECT_NEAR(cell.unknown(), ev.min_unknown, 1e-5);
  // Enough free observations must eventually flip a wall that moved away.
  for (int i = 0; i < 500; ++i) cell = ev.update(cell, ev.pass());
  EXPECT_GT(cell.free, cell.occupied);
}

TEST(EvidenceModel, RejectsOutOfRangeValues) {
  EvidenceModel ev;
  ev.hit_occupied = 1.0f;
  EXPECT_THROW(ev.validate(), ConfigError);
  ev = {};
  ev.pass_free = 0.0f;
  EXPECT_THROW(ev.validate(), ConfigError);
}

TEST(EvidenceModel, PassedUpdateEqualsTheGeneralUpdateToTheBit) {
  const EvidenceModel ev;
  int compared = 0;
  for (int i = 0; i <= 50; ++i)
    for (int j = 0; i + j <= 50; ++j) {
      const DsMass m{0.02f * static_cast<float>(i), 0.02f * static_cast<float>(j)};
      const DsMass general = ev.update(m, ev.pass()), passed = ev.update_passed(m);
      EXPECT_EQ(general.occupied, passed.occupied) << i << " " << j;
      EXPECT_EQ(general.free, passed.free) << i << " " << j;
      ++compared;
    }
  EXPECT_EQ(compared, 1326);
}

}  // namespace
}  // namespace dsswarm
