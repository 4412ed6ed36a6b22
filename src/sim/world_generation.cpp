// The generated office building. Bands from bottom to top:
//   row 0, corridor 0, row 1, row 2, corridor 1, row 3, ...
// so each corridor serves the room row below and the one above it. With more
// than one corridor a vertical spine corridor along the left outer wall joins
// them. Every room has one doorway onto its corridor; clutter keeps out of a
// lane behind each door so a robot can always get in.
#include <algorithm>
#include <cmath>
#include <string>

#include "common/errors.hpp"
#include "common/rng.hpp"
#include "sim/world.hpp"

namespace dsswarm {
namespace {

// Lane behind each door kept free of clutter, and the points on its axis.
constexpr double kLaneHalfWidth = 1.0;
constexpr double kLaneMaxDepth = 3.0;
constexpr double kInsideDoorDepth = 0.9;
constexpr double kSafeSpotBeforeLaneEnd = 0.8;
// Doors keep this far from room corners (beyond half the door and half a wall).
constexpr double kDoorCornerMargin = 0.4;
constexpr double kMinRoomSize = 3.0;

struct Layout {
  int n_corridors;
  double spine_width;  // 0 when there is a single corridor
  double room_width, room_depth;
};

Layout layout_of(const WorldConfig& c) {
  Layout l{};
  l.n_corridors = (c.rooms_y + 1) / 2;
  l.spine_width = l.n_corridors > 1 ? c.corridor_width : 0.0;
  l.room_width = (c.width - l.spine_width) / c.rooms_x;
  l.room_depth = (c.height - l.n_corridors * c.corridor_width) / c.rooms_y;
  return l;
}

// Clutter inside one room: boxes and pillars, clear of the door lane, the walls and each other.
void place_clutter(const WorldConfig& config, const Room& room, const Box& lane, Rng& rng, std::vector<Box>& solids) {
  constexpr int kAttempts = 50;
  constexpr double kWallGap = 0.3, kItemGap = 0.6;
  const Box interior = room.area.expanded(-(config.wall_thickness / 2 + kWallGap));
  std::vector<Box> placed;
  for (int item = 0; item < config.clutter_per_room; ++item) {
    for (int attempt = 0; attempt < kAttempts; ++attempt) {
      const bool pillar = rng.uniform() < 0.35;
      const double sx = pillar ? rng.uniform(0.25, 0.45) : rng.uniform(0.4, 1.5);
      const double sy = pillar ? sx : rng.uniform(0.4, 1.5);
      const Eigen::Vector2d room_span = interior.max - interior.min;
      if (room_span.x() <= sx || room_span.y() <= sy) continue;
      const Eigen::Vector2d centre(rng.uniform(interior.min.x() + sx / 2, interior.max.x() - sx / 2),
                                   rng.uniform(interior.min.y() + sy / 2, interior.max.y() - sy / 2));
      const Eigen::Vector2d half(sx / 2, sy / 2);
      const Box candidate{centre - half, centre + half};
      if (candidate.overlaps(lane)) continue;
      if (std::any_of(placed.begin(), placed.end(),
                      [&](const Box& b) { return b.expanded(kItemGap).overlaps(candidate); }))
        continue;
      placed.push_back(candidate);
      break;
    }
  }
  solids.insert(solids.end(), placed.begin(), placed.end());
}

// Walls, rooms and the lanes behind their doors, as generate_world lays them out.
struct WorldBuilder {
  const WorldConfig& config;
  const Layout l;
  const double half_t;
  Rng& rng;
  std::vector<Box> solids;
  BuildingLayout layout;
  std::vector<Box> lanes;

  // Walls are thin boxes centred on their lines, overlapping at the corners.
  void horizontal_wall(double xa, double xb, double y) { solids.push_back({{xa, y - half_t}, {xb, y + half_t}}); }
  void vertical_wall(double x, double ya, double yb) { solids.push_back({{x - half_t, ya}, {x + half_t, yb}}); }

  // Row `row` of rooms from y0: its walls and each room with a door onto its corridor.
  void room_row(int row, double y0) {
    const double x0 = l.spine_width, y1 = y0 + l.room_depth, w = config.width;
    const bool corridor_above = row % 2 == 0;
    if (l.spine_width > 0) vertical_wall(x0, y0 - half_t, y1 + half_t);
    for (int i = 1; i < config.rooms_x; ++i) vertical_wall(x0 + i * l.room_width, y0 - half_t, y1 + half_t);
    if (!corridor_above && row + 1 < config.rooms_y) horizontal_wall(x0 - half_t, w + half_t, y1);
    for (int i = 0; i < config.rooms_x; ++i) room(row, x0 + i * l.room_width, y0, corridor_above);
  }

  void room(int row, double xa, double y0, bool corridor_above) {
    const double xb = xa + l.room_width, y1 = y0 + l.room_depth;
    const double door_wall_y = corridor_above ? y1 : y0;
    const Eigen::Vector2d into_room(0.0, corridor_above ? -1.0 : 1.0);
    const double lane_depth = std::min(kLaneMaxDepth, l.room_depth - 1.0);
    const double margin = config.door_width / 2 + half_t + kDoorCornerMargin;
    const double door_x = rng.uniform(xa + margin, xb - margin);
    horizontal_wall(xa - half_t, door_x - config.door_width / 2, door_wall_y);
    horizontal_wall(door_x + config.door_width / 2, xb + half_t, door_wall_y);

    Room r;
    r.area = {{xa, y0}, {xb, y1}};
    r.door = {door_x, door_wall_y};
    r.into_room = into_room;
    r.inside_door = r.door + kInsideDoorDepth * into_room;
    r.safe_spot = r.door + (lane_depth - kSafeSpotBeforeLaneEnd) * into_room;
    r.corridor = row / 2;
    layout.rooms.push_back(r);
    const Eigen::Vector2d lane_end = r.door + lane_depth * into_room;
    lanes.push_back({{door_x - kLaneHalfWidth, std::min(door_wall_y, lane_end.y())},
                     {door_x + kLaneHalfWidth, std::max(door_wall_y, lane_end.y())}});
  }
};

}  // namespace

void validate(const WorldConfig& c) {
  require_config("world config", std::isfinite(c.width) && c.width > 0, "width must be a positive number of metres");
  require_config("world config", std::isfinite(c.height) && c.height > 0, "height must be a positive number of metres");
  require_config("world config", c.rooms_x >= 1 && c.rooms_x <= 1000, "rooms_x must be in [1, 1000]");
  require_config("world config", c.rooms_y >= 1 && c.rooms_y <= 1000, "rooms_y must be in [1, 1000]");
  require_config("world config", std::isfinite(c.wall_thickness) && c.wall_thickness > 0 && c.wall_thickness <= 0.5,
          "wall_thickness must be in (0, 0.5] m");
  // A robot keeps 0.4 m from every wall, plus a margin for steering.
  require_config("world config", std::isfinite(c.door_width) && c.door_width >= 0.9, "door_width must be >= 0.9 m");
  require_config("world config", std::isfinite(c.corridor_width) && c.corridor_width >= 1.0 + c.wall_thickness,
          "corridor_width must be >= 1.0 m plus the wall thickness");
  require_config("world config", c.clutter_per_room >= 0 && c.clutter_per_room <= 50, "clutter_per_room must be in [0, 50]");
  const Layout l = layout_of(c);
  require_config("world config", l.room_width >= kMinRoomSize && l.room_width >= c.door_width + c.wall_thickness + 2 * kDoorCornerMargin,
          "width too small for rooms_x rooms of at least 3 m");
  require_config("world config", l.room_depth >= kMinRoomSize, "height too small for rooms_y rows of rooms (and corridors) at least 3 m deep");
}

World generate_world(const WorldConfig& config) {
  validate(config);
  Rng rng(config.seed);
  WorldBuilder b{config, layout_of(config), config.wall_thickness / 2, rng, {}, {}, {}};
  const double w = config.width, h = config.height, half_t = b.half_t;
  b.horizontal_wall(-half_t, w + half_t, 0.0);
  b.horizontal_wall(-half_t, w + half_t, h);
  b.vertical_wall(0.0, -half_t, h + half_t);
  b.vertical_wall(w, -half_t, h + half_t);
  double y = 0.0;
  for (int row = 0; row < config.rooms_y; ++row) {
    b.room_row(row, y);
    y += b.l.room_depth;
    if (row % 2 == 0) {  // the corridor above it
      const double cw = config.corridor_width, yc = y + cw / 2;
      b.layout.corridors.push_back({{cw / 2, yc}, {w - cw / 2, yc}});
      y += cw;
    }
  }
  // Clutter after the walls, so the door positions do not depend on clutter_per_room.
  for (std::size_t k = 0; k < b.layout.rooms.size(); ++k)
    place_clutter(config, b.layout.rooms[k], b.lanes[k], rng, b.solids);
  return World({}, std::move(b.solids), std::move(b.layout));
}

}  // namespace dsswarm
