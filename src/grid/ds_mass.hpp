#pragma once
// Dempster–Shafer belief masses of one map cell over the frame {occupied, free}.
// Focal sets: {occupied}, {free}, and Θ = {occupied, free} ("unknown").
// Only occupied and free are stored; unknown = 1 − occupied − free.
#include <algorithm>

namespace dsswarm {

struct DsMass {
  float occupied = 0.0f;
  float free = 0.0f;

  constexpr float unknown() const { return 1.0f - occupied - free; }

  // Pignistic-style occupancy used for scoring and display: unknown counts half.
  constexpr float occupancy() const { return 0.5f + 0.5f * (occupied - free); }

  static constexpr DsMass vacuous() { return {0.0f, 0.0f}; }
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
  const float occ = (a.occupied * b.occupied + a.occupied * ub + ua * b.occupied) / norm;
  const float fr = (a.free * b.free + a.free * ub + ua * b.free) / norm;
  // Clamp rounding so masses stay a valid distribution.
  const float o = std::clamp(occ, 0.0f, 1.0f);
  return {o, std::clamp(fr, 0.0f, 1.0f - o)};
}

}  // namespace dsswarm
