#pragma once
// Dempster–Shafer belief masses of one map cell over the frame {occupied, free}.
// Focal sets: {occupied}, {free}, and Θ = {occupied, free} ("unknown").
// Only occupied and free are stored; unknown = 1 − occupied − free.
#include <algorithm>
#include <cstdint>

namespace dsswarm {

struct DsMass {
  float occupied = 0.0f;
  float free = 0.0f;

  constexpr float unknown() const { return 1.0f - occupied - free; }

  // Pignistic-style occupancy used for scoring and display: unknown counts half.
  constexpr float occupancy() const { return 0.5f + 0.5f * (occupied - free); }

  static constexpr DsMass vacuous() { return {0.0f, 0.0f}; }
};

// A cell's masses as stored in a grid: 16-bit fixed point, 4 bytes instead of
// 8. Steps of 1/65535 lie far below the smallest evidence the model adds, and
// rounding keeps occupied + free <= 1 so every stored mass stays valid.
struct PackedMass {
  std::uint16_t occupied = 0;
  std::uint16_t free = 0;

  static constexpr float kOne = 65535.0f;

  constexpr bool vacuous() const { return occupied == 0 && free == 0; }
  constexpr bool operator==(const PackedMass&) const = default;
  constexpr DsMass mass() const {
    DsMass m = unguarded_mass();
    m.free = std::min(m.free, 1.0f - m.occupied);  // float rounding must not make the sum exceed 1
    return m;
  }
  // For insertion's read-update-write of a cell: the update takes slightly
  // invalid masses (a sum 1 ulp above 1) and returns valid ones, so neither
  // side needs mass()'s and pack()'s guards.
  constexpr DsMass unguarded_mass() const {
    return {static_cast<float>(occupied) * (1.0f / kOne), static_cast<float>(free) * (1.0f / kOne)};
  }
  static constexpr PackedMass pack_valid(const DsMass& m) {
    const auto o = static_cast<std::uint32_t>(m.occupied * kOne + 0.5f);
    const auto f = std::min(static_cast<std::uint32_t>(m.free * kOne + 0.5f), 65535u - o);
    return {static_cast<std::uint16_t>(o), static_cast<std::uint16_t>(f)};
  }
  static constexpr PackedMass pack(const DsMass& m) {
    // max/min in this order map NaN to 0 and compile to two instructions.
    const auto unit = [](float v) { return std::min(std::max(0.0f, v), 1.0f); };
    return pack_valid({unit(m.occupied), unit(m.free)});
  }
};

// Dempster's rule of combination.
//   occ = (o1·o2 + o1·u2 + u1·o2) / (1 − K)
//   free = (f1·f2 + f1·u2 + u1·f2) / (1 − K)
//   K = o1·f2 + f1·o2 (mass on the empty set: the two sources contradict)
// Commutative and associative; the vacuous mass (all unknown) is the identity.
// Total conflict (K = 1: one source certainly occupied, the other certainly free)
// has no Dempster combination; we return the vacuous mass ("we do not know")
// rather than NaN — the evidence model never produces certain masses, so this
// only guards against hand-made input.
constexpr DsMass combine(const DsMass& a, const DsMass& b) {
  const float ua = a.unknown(), ub = b.unknown();
  const float conflict = a.occupied * b.free + a.free * b.occupied;
  const float norm = 1.0f - conflict;
  if (norm <= 1e-6f) return DsMass::vacuous();
  const float inv = 1.0f / norm;  // one division, not two: insertion does this for every cell
  const float occ = (a.occupied * b.occupied + a.occupied * ub + ua * b.occupied) * inv;
  const float fr = (a.free * b.free + a.free * ub + ua * b.free) * inv;
  // Clamp rounding so masses stay a valid distribution.
  const float o = std::clamp(occ, 0.0f, 1.0f);
  return {o, std::clamp(fr, 0.0f, 1.0f - o)};
}

}  // namespace dsswarm
