#include "apps/swarm_picture.hpp"

#include <algorithm>
#include <cstdint>

#include "io/maps/annotate.hpp"

namespace dsswarm {
namespace {

constexpr Rgb kAccepted{0, 0, 0};
constexpr Rgb kRejected{220, 30, 30};
constexpr Rgb kHole{255, 255, 255};
constexpr Rgb kStart{90, 90, 90};
constexpr Rgb kPastMap{185, 185, 185};  // the legend's mark for a path drawn pale

// How many of robot i's first poses the first robot's map covers: all of
// its own; of another, those up to the version of the layer it holds
// (everything when the versions are not known).
std::size_t covered(const SwarmRunResult& s, std::size_t i) {
  const SwarmAgentResult& a = s.agents[i];
  if (i == 0 || a.map_versions.size() != a.trajectory.size()) return a.trajectory.size();
  const MapLayer* held = s.agents.front().held(a.name);
  const std::uint64_t version = held ? held->version : 0;
  const auto past = std::upper_bound(a.map_versions.begin(), a.map_versions.end(), version);
  return static_cast<std::size_t>(past - a.map_versions.begin());
}

// Marker radii in pixels, grown with the picture's scale so they stay visible.
int radius(const Image& image, const GridRaster& raster, int base) {
  return base * std::max(1, image.width / std::max(1, raster.width) / 2);
}

// Encounters where agent 0's frame can place robot a. Returns which kinds were drawn.
std::pair<bool, bool> draw_encounters(Image& picture, const SwarmRunResult& s, const GridRaster& raster,
                                      const std::vector<std::optional<Pose2>>& frames) {
  bool accepted = false, rejected = false;
  const int r = radius(picture, raster, 5);
  for (const EncounterRecord& e : s.encounters) {
    for (std::size_t i = 0; i < s.agents.size(); ++i) {
      if (s.agents[i].name != e.a || !frames[i]) continue;
      const Eigen::Vector2d at = *frames[i] * e.a_pose_in_a.translation();
      draw_marker(picture, raster, at, e.accepted ? kAccepted : kRejected, r);
      if (!e.accepted) draw_marker(picture, raster, at, kHole, r - r / 3 - 1);
      (e.accepted ? accepted : rejected) = true;
    }
  }
  return {accepted, rejected};
}

}  // namespace

Rgb pale(Rgb c) {
  constexpr double kShare = 0.6;  // of the way from the colour to white
  auto toward_white = [](std::uint8_t v) { return static_cast<std::uint8_t>(v + kShare * (255 - v) + 0.5); };
  return {toward_white(c.r), toward_white(c.g), toward_white(c.b)};
}

Image swarm_picture(const SwarmRunResult& s, const GridRaster& raster, const std::vector<std::optional<Pose2>>& frames) {
  Image picture = render_map(raster, fitting_scale(raster));
  std::vector<LegendEntry> legend;
  bool past_map = false;
  for (std::size_t i = 0; i < s.agents.size(); ++i) {
    if (!frames[i]) continue;
    const Rgb colour = agent_colour(static_cast<int>(i));
    std::vector<Eigen::Vector2d> pts;
    for (const StampedPose& p : s.agents[i].trajectory) pts.push_back(*frames[i] * p.pose.translation());
    // Past the map the first robot holds of it, pale: that ground is not in this map.
    const std::size_t n = std::max<std::size_t>(covered(s, i), 1);
    if (n < pts.size()) {
      draw_path(picture, raster, {pts.begin() + static_cast<std::ptrdiff_t>(n - 1), pts.end()}, pale(colour));
      pts.resize(n);
      past_map = true;
    }
    draw_path(picture, raster, pts, colour);
    legend.push_back({s.agents[i].name, colour, LegendEntry::Mark::Line});
  }
  if (past_map) legend.push_back({"past the map held", kPastMap, LegendEntry::Mark::Line});
  // Starts on top of the paths, encounters on top of everything.
  for (std::size_t i = 0; i < s.agents.size(); ++i)
    if (frames[i] && !s.agents[i].trajectory.empty())
      draw_ringed_marker(picture, raster, *frames[i] * s.agents[i].trajectory.front().pose.translation(),
                         agent_colour(static_cast<int>(i)), radius(picture, raster, 4));
  legend.push_back({"start", kStart, LegendEntry::Mark::Disc});
  const auto [accepted, rejected] = draw_encounters(picture, s, raster, frames);
  if (accepted) legend.push_back({"encounter, merged", kAccepted, LegendEntry::Mark::Disc});
  if (rejected) legend.push_back({"encounter, not merged", kRejected, LegendEntry::Mark::Ring});
  const double metres_per_pixel = raster.resolution * raster.width / picture.width;
  return with_legend(picture, metres_per_pixel, legend);
}

}  // namespace dsswarm
