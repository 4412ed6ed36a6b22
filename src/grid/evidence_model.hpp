#pragma once
// How one laser beam turns into Dempster–Shafer evidence.
//
// A beam that ends in a cell says "occupied" with mass `hit_occupied` (the rest
// stays unknown: the hit may be noise, or the cell only partly filled). Cells
// the beam passes through get "free" with mass `pass_free`. Beams with no
// return (max range, NaN) give no evidence at all.
//
// After each combination a cell keeps at least `min_unknown` of unknown mass
// (Shafer discounting). Without it, repeated hits drive a cell to certainty,
// and Dempster's rule then ignores any later contrary evidence forever: a cell
// certainly occupied can never be revised, however often it is seen free.
#include <algorithm>
#include <cstdint>

#include "common/errors.hpp"
#include "grid/ds_mass.hpp"

namespace dsswarm {

struct EvidenceModel {
  float hit_occupied = 0.4f;   // mass on {occupied} for the cell a beam ends in
  float pass_free = 0.04f;     // mass on {free} for each cell a beam passes through
  float min_unknown = 0.02f;   // floor on a cell's unknown mass after combination

  DsMass hit() const { return {hit_occupied, 0.0f}; }
  DsMass pass() const { return {0.0f, pass_free}; }

  // Dempster combination followed by discounting to keep `min_unknown`.
  DsMass update(const DsMass& cell, const DsMass& evidence) const { return discounted(combine(cell, evidence)); }

  // update(cell, pass()), the commonest update (every cell a beam crosses),
  // with the products by pass()'s zero occupied mass left out: the same
  // result to the bit, for fewer operations.
  DsMass update_passed(const DsMass& cell) const {
    const float ua = cell.unknown(), ub = 1.0f - pass_free;
    const float norm = 1.0f - cell.occupied * pass_free;
    if (norm <= 1e-6f) return DsMass::vacuous();
    const float inv = 1.0f / norm;
    const float occ = cell.occupied * ub * inv;
    const float fr = (cell.free * pass_free + cell.free * ub + ua * pass_free) * inv;
    const float o = std::clamp(occ, 0.0f, 1.0f);
    return discounted({o, std::clamp(fr, 0.0f, 1.0f - o)});
  }

  // pack_valid(update_passed(m)).free for a stored cell with no occupied mass
  // (open space, most of what beams cross) and free mass `free`: the same
  // operations with the ones that multiply or add that zero left out, so the
  // same result to the bit (checked for all 65536 values). Its occupied mass
  // stays 0. Insertion reads it from a table (MultiResMap).
  std::uint16_t passed_free(std::uint16_t free) const {
    const float f = static_cast<float>(free) * (1.0f / PackedMass::kOne);
    const float ub = 1.0f - pass_free;
    float fr = std::clamp(f * pass_free + f * ub + (1.0f - f) * pass_free, 0.0f, 1.0f);
    if (1.0f - fr < min_unknown) fr *= (1.0f - min_unknown) / fr;
    return static_cast<std::uint16_t>(std::min(static_cast<std::uint32_t>(fr * PackedMass::kOne + 0.5f), 65535u));
  }

  // Shafer discounting: scales the evidence down to leave `min_unknown`.
  DsMass discounted(DsMass m) const {
    if (m.unknown() < min_unknown) {
      const float scale = (1.0f - min_unknown) / (m.occupied + m.free);
      m.occupied *= scale;
      m.free *= scale;
    }
    return m;
  }

  void validate() const {
    auto in_open_unit = [](float v) { return v > 0.0f && v < 1.0f; };
    if (!in_open_unit(hit_occupied)) throw ConfigError("evidence.hit_occupied must be in (0, 1)");
    if (!in_open_unit(pass_free)) throw ConfigError("evidence.pass_free must be in (0, 1)");
    if (!(min_unknown >= 0.0f && min_unknown < 0.5f)) throw ConfigError("evidence.min_unknown must be in [0, 0.5)");
  }
};

}  // namespace dsswarm
