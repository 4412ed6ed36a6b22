#pragma once
// A static 2D world made of line segments: a generated office building (rooms
// on both sides of corridors, doorways, clutter) or any hand-built set of
// walls. The world knows nothing about robots, so several simulated robots
// can share one world.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace dsswarm {

class Rng;

struct Segment {
  Eigen::Vector2d a;
  Eigen::Vector2d b;
};

// Axis-aligned rectangle; as an obstacle it is solid (its inside is not free).
struct Box {
  Eigen::Vector2d min;
  Eigen::Vector2d max;

  bool contains(const Eigen::Vector2d& p) const {
    return p.x() >= min.x() && p.x() <= max.x() && p.y() >= min.y() && p.y() <= max.y();
  }
  bool overlaps(const Box& o) const {
    return min.x() < o.max.x() && o.min.x() < max.x() && min.y() < o.max.y() && o.min.y() < max.y();
  }
  // Grown (margin > 0) or shrunk (margin < 0) by `margin` on every side.
  Box expanded(double margin) const {
    return {min - Eigen::Vector2d(margin, margin), max + Eigen::Vector2d(margin, margin)};
  }
};

// One room of a generated building, with the landmarks a tour needs.
struct Room {
  Box area;                   // between the wall centre lines
  Eigen::Vector2d door;       // doorway centre, on the wall centre line
  Eigen::Vector2d into_room;  // unit vector from the corridor through the door into the room
  Eigen::Vector2d inside_door;  // just inside the doorway, on the door axis
  Eigen::Vector2d safe_spot;    // deeper on the door axis; clutter never blocks door -> here
  int corridor = 0;             // index into BuildingLayout::corridors
};

// Free centre line of a corridor. Corridors are joined at their `begin` ends
// (by a spine corridor when there are several), so begin -> begin is free.
struct Corridor {
  Eigen::Vector2d begin;
  Eigen::Vector2d end;
};

struct BuildingLayout {
  std::vector<Room> rooms;
  std::vector<Corridor> corridors;
};

struct WorldConfig {
  std::uint64_t seed = 1;
  double width = 30, height = 20;  // metres, outer wall centre lines
  int rooms_x = 4, rooms_y = 2;    // rooms per row, rows of rooms (a corridor serves two rows)
  double corridor_width = 2.0;     // between wall centre lines
  double door_width = 1.0;         // free opening
  int clutter_per_room = 2;        // boxes / pillars per room (fewer if they do not fit)
  double wall_thickness = 0.1;
};

// Throws ConfigError naming the field when the building cannot be laid out
// with room for a robot (0.4 m clearance) to drive through it.
void validate(const WorldConfig& config);

class World {
 public:
  // `walls`: free-standing segments (zero thickness); `solids`: filled boxes
  // (their 4 edges become segments, their inside is never free).
  explicit World(std::vector<Segment> walls, std::vector<Box> solids = {}, BuildingLayout layout = {});

  // Distance along the ray to the nearest segment, or +infinity when nothing
  // is hit within max_range.
  double raycast(const Eigen::Vector2d& origin, double angle, double max_range) const;

  // Distance from p to the nearest wall; 0 inside a solid box.
  double clearance(const Eigen::Vector2d& p) const;
  bool is_free(const Eigen::Vector2d& p, double clearance) const;
  // Whether every point of the straight segment a -> b is free with `clearance`.
  bool is_segment_free(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double clearance) const;

  // A deterministic tour of a generated building: along the corridors, into
  // rooms through their doorways, back along the corridors to the start and
  // once more into an already visited room (a loop for SLAM to close).
  // Every leg keeps >= 0.45 m clearance. Empty for worlds without rooms.
  std::vector<Eigen::Vector2d> waypoint_tour(std::uint64_t seed) const;

  const std::vector<Segment>& segments() const { return segments_; }
  const std::vector<Box>& solids() const { return solids_; }
  const BuildingLayout& layout() const { return layout_; }
  // Bounding box of all segments.
  const Box& bounds() const { return bounds_; }

 private:
  void build_grid();
  // The part [t_enter, t_leave] of the ray that lies inside the grid's
  // rectangle (slab method); false when it misses the rectangle.
  bool clip_to_grid(const Eigen::Vector2d& origin, const Eigen::Vector2d& dir, double& t_enter,
                    double& t_leave) const;
  // The nearest hit along the ray among one grid cell's segments, if nearer than `best`.
  double nearest_in_cell(std::size_t cell, const Eigen::Vector2d& origin, const Eigen::Vector2d& dir,
                         double best) const;

  std::vector<Segment> segments_;
  std::vector<Box> solids_;
  BuildingLayout layout_;
  Box bounds_;

  // Uniform grid of segment buckets for raycasting (CSR layout).
  Eigen::Vector2d grid_min_;
  double cell_size_ = 1.0;
  int grid_nx_ = 1, grid_ny_ = 1;
  std::vector<std::uint32_t> cell_begin_;     // grid_nx_*grid_ny_ + 1 offsets
  std::vector<std::uint32_t> cell_segments_;  // segment indices
};

World generate_world(const WorldConfig& config);

// The spot a tour drives to inside `room`: random, 1.5-3 m in from the door,
// reachable in a straight line (0.6 m clearance) from room.inside_door; the
// room's safe_spot when no such spot is found. (waypoint_tour uses it; the
// swarm simulation too, so its robots look into rooms the same way.)
Eigen::Vector2d pick_room_spot(const World& world, const Room& room, Rng& rng);

}  // namespace dsswarm
