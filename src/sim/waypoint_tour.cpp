// A tour of a generated building. Per corridor: drive out along it and visit
// a random half of its rooms, come back and visit the others on the way, return to the
// corridor's start and move on (along the spine) to the next corridor. At the
// end, back to the first corridor's start and once more into its nearest
// room: the robot re-observes places it mapped minutes earlier, which is what
// loop closure in SLAM needs.
#include <algorithm>
#include <cmath>

#include "common/rng.hpp"
#include "sim/world.hpp"

namespace dsswarm {
namespace {

// Legs inside rooms keep this clearance; doorways (0.5 m for a 1 m door) and
// corridors give at least 0.45 m by construction.
constexpr double kRoomLegClearance = 0.6;
constexpr int kSpotAttempts = 40;
// How deep into a room the tour goes (metres from the door): deep enough to
// see the whole room, short enough that the default demo stays a few minutes.
constexpr double kSpotMinDepth = 1.5, kSpotMaxDepth = 3.0;
constexpr double kSpotMaxSideways = 1.5;  // from the door axis
constexpr double kSpotSideMargin = 1.0;   // from the room walls

// Point on the corridor centre line in front of the room's door.
Eigen::Vector2d in_front_of_door(const Room& room, const Corridor& corridor) {
  const Eigen::Vector2d axis = (corridor.end - corridor.begin).normalized();
  return corridor.begin + (room.door - corridor.begin).dot(axis) * axis;
}

}  // namespace

Eigen::Vector2d pick_room_spot(const World& world, const Room& room, Rng& rng) {
  const Eigen::Vector2d across(-room.into_room.y(), room.into_room.x());
  const Box area = room.area.expanded(-kSpotSideMargin);
  const Eigen::Vector2d room_size = room.area.max - room.area.min;
  const double room_depth = std::abs(room_size.dot(room.into_room));
  const double max_depth = std::min(kSpotMaxDepth, room_depth - kSpotSideMargin);
  for (int attempt = 0; attempt < kSpotAttempts && max_depth > kSpotMinDepth; ++attempt) {
    const double depth = rng.uniform(kSpotMinDepth, max_depth);
    // Lateral range: whatever stays inside the room's shrunk area.
    const Eigen::Vector2d on_axis = room.door + depth * room.into_room;
    const double lo = std::max(-kSpotMaxSideways,
                               std::min((area.min - on_axis).dot(across), (area.max - on_axis).dot(across)));
    const double hi = std::min(kSpotMaxSideways,
                               std::max((area.min - on_axis).dot(across), (area.max - on_axis).dot(across)));
    if (hi <= lo) break;
    const Eigen::Vector2d spot = on_axis + rng.uniform(lo, hi) * across;
    if (world.is_segment_free(room.inside_door, spot, kRoomLegClearance)) return spot;
  }
  return room.safe_spot;
}

std::vector<Eigen::Vector2d> World::waypoint_tour(std::uint64_t seed) const {
  const auto& rooms = layout_.rooms;
  const auto& corridors = layout_.corridors;
  if (rooms.empty() || corridors.empty()) return {};
  Rng rng(seed);
  std::vector<Eigen::Vector2d> tour;
  auto go = [&](const Eigen::Vector2d& p) {
    if (tour.empty() || (tour.back() - p).norm() > 1e-6) tour.push_back(p);
  };
  auto visit = [&](const Room& room) {
    const Eigen::Vector2d front = in_front_of_door(room, corridors[static_cast<std::size_t>(room.corridor)]);
    go(front);
    go(room.inside_door);
    go(pick_room_spot(*this, room, rng));
    go(room.inside_door);
    go(front);
  };

  const Room* first_room_of_first_corridor = nullptr;
  for (std::size_t c = 0; c < corridors.size(); ++c) {
    const Corridor& corridor = corridors[c];
    const Eigen::Vector2d axis = (corridor.end - corridor.begin).normalized();
    std::vector<const Room*> along;
    for (const Room& r : rooms)
      if (r.corridor == static_cast<int>(c)) along.push_back(&r);
    auto position = [&](const Room* r) { return (r->door - corridor.begin).dot(axis); };
    std::stable_sort(along.begin(), along.end(), [&](const Room* a, const Room* b) { return position(a) < position(b); });
    if (c == 0 && !along.empty()) first_room_of_first_corridor = along.front();

    std::vector<const Room*> outward, homeward;
    for (const Room* r : along) (rng.uniform() < 0.5 ? outward : homeward).push_back(r);
    go(corridor.begin);
    for (const Room* r : outward) visit(*r);
    // Outward visits end at the far room; the corridor's end wall is in lidar range anyway.
    for (auto it = homeward.rbegin(); it != homeward.rend(); ++it) visit(**it);
    go(corridor.begin);
  }
  go(corridors.front().begin);
  if (first_room_of_first_corridor != nullptr) visit(*first_room_of_first_corridor);
  return tour;
}

}  // namespace dsswarm
