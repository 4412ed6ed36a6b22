#include "grid/ds_mass.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "grid/ds_grid.hpp"
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

TEST(PackedMass, RoundTripsWithinHalfAStepAndStaysAValidMass) {
  for (int i = 0; i <= 200; ++i)
    for (int j = 0; j <= 200 - i; ++j) {
      const DsMass m{static_cast<float>(i) / 200.0f, static_cast<float>(j) / 200.0f};
      const PackedMass p = PackedMass::pack(m);
      const DsMass back = p.mass();
      EXPECT_NEAR(back.occupied, m.occupied, 0.5f / PackedMass::kOne + 1e-7f);
      EXPECT_NEAR(back.free, m.free, 0.5f / PackedMass::kOne + 1e-7f);
      EXPECT_LE(std::uint32_t{p.occupied} + p.free, 65535u);
      EXPECT_EQ(PackedMass::pack(back).occupied, p.occupied);  // stable: re-packing changes nothing
      EXPECT_EQ(PackedMass::pack(back).free, p.free);
    }
  EXPECT_TRUE(PackedMass::pack(DsMass::vacuous()).vacuous());
  const PackedMass bad = PackedMass::pack({std::numeric_limits<float>::quiet_NaN(), 2.0f});
  EXPECT_EQ(bad.occupied, 0);
  EXPECT_EQ(bad.free, 65535);
}

TEST(PackedMass, CellsUpdatedInAGridFollowTheFloatModel) {
  // 16-bit storage rounds after every update; the rounding must not add up
  // over the hundreds of updates a wall cell sees.
  const EvidenceModel ev;
  DsGrid grid(0.05);
  DsMass cell;
  const auto step = [&](const DsMass& evidence) {
    cell = ev.update(cell, evidence);
    grid.update({3, 4}, [&](const DsMass& m) { return ev.update(m, evidence); });
    EXPECT_NEAR(grid.at({3, 4}).occupied, cell.occupied, 2e-4f);
    EXPECT_NEAR(grid.at({3, 4}).free, cell.free, 2e-4f);
  };
  for (int i = 0; i < 300; ++i) step(ev.hit());
  for (int i = 0; i < 300; ++i) step(ev.pass());
  EXPECT_GT(grid.at({3, 4}).free, grid.at({3, 4}).occupied);  // the wall that moved away is revised
  for (int i = 0; i < 300; ++i) step(i % 3 == 0 ? ev.hit() : ev.pass());
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

// Insertion's shortcut for open space must change nothing: every stored
// free mass, under the default model and one that caps early.
TEST(EvidenceModel, PassedFreeIsTheGeneralPassToTheBit) {
  EvidenceModel capped_early;
  capped_early.pass_free = 0.3f;
  capped_early.min_unknown = 0.1f;
  for (const EvidenceModel& ev : {EvidenceModel{}, capped_early}) {
    int differing = 0;
    for (std::uint32_t f = 0; f <= 65535; ++f) {
      const PackedMass cell{0, static_cast<std::uint16_t>(f)};
      const PackedMass general = PackedMass::pack_valid(ev.update_passed(cell.unguarded_mass()));
      if (general.occupied != 0 || general.free != ev.passed_free(cell.free)) ++differing;
    }
    EXPECT_EQ(differing, 0) << "pass_free " << ev.pass_free;
  }
}

}  // namespace
}  // namespace dsswarm
