#pragma once
// The plan the simulated swarm drives (swarm_sim.cpp): parking spots at the
// rendezvous, start spots, each robot's share of the rooms and its route
// along the shared corridors. Kept apart from the simulation itself, which
// only turns the routes into scans.
#include <algorithm>
#include <cmath>
#include <vector>

#include "sim/world.hpp"

namespace dsswarm {

class Rng;

namespace sim_detail {

// A place on the corridor network: distance `s` along a corridor's centre line from its begin.
struct NetworkPoint {
  int corridor = 0;
  double s = 0.0;
};

// The free centre lines of the corridors, joined at their begin ends (by the
// spine): every route runs along them, so robots share the corridors and
// meet there.
class CorridorNetwork {
 public:
  explicit CorridorNetwork(const std::vector<Corridor>& corridors) : corridors_(corridors) {}

  const Corridor& corridor(int c) const { return corridors_[static_cast<std::size_t>(c)]; }
  Eigen::Vector2d axis(int c) const { return (corridor(c).end - corridor(c).begin).normalized(); }
  double length(int c) const { return (corridor(c).end - corridor(c).begin).norm(); }
  Eigen::Vector2d point(const NetworkPoint& p) const { return corridor(p.corridor).begin + p.s * axis(p.corridor); }
  NetworkPoint project(int c, const Eigen::Vector2d& p) const {
    return {c, std::clamp((p - corridor(c).begin).dot(axis(c)), 0.0, length(c))};
  }

  double distance(const NetworkPoint& a, const NetworkPoint& b) const {
    if (a.corridor == b.corridor) return std::abs(a.s - b.s);
    return a.s + (corridor(a.corridor).begin - corridor(b.corridor).begin).norm() + b.s;
  }

  // Waypoints from a to b (a itself is not emitted).
  template <typename Go>
  void route(const NetworkPoint& a, const NetworkPoint& b, Go&& go) const {
    if (a.corridor != b.corridor) {
      go(corridor(a.corridor).begin);
      go(corridor(b.corridor).begin);
    }
    go(point(b));
  }

 private:
  const std::vector<Corridor>& corridors_;
};

struct StartSpot {
  Eigen::Vector2d position;
  int room = -1;  // or -1 on a corridor
  int corridor = 0;
};

// Parking spots on a square grid around the rendezvous centre, nearest first:
// free, and reachable from the centre in a straight line.
std::vector<Eigen::Vector2d> parking_spots(const World& world, const Eigen::Vector2d& centre, int robots);

// Random start spots in rooms (on the door axis) and corridors, pairwise at
// least kMinStartSeparation apart and as far from every parking spot.
std::vector<StartSpot> pick_starts(const World& world, const CorridorNetwork& network,
                                   const std::vector<Eigen::Vector2d>& parking, int robots, Rng& rng);

// Each robot gets a home corridor (robots spread evenly over the corridors);
// a corridor's rooms are dealt round-robin by position among the robots at
// home there, so every robot drives the length of its corridor and each
// corridor is seen by several robots. On top, each robot visits one room of
// someone else's share, so that maps also overlap inside rooms. A robot's
// start room is not revisited. (Maps of different corridors overlap where
// robots start away from home, on the spine and at the rendezvous.)
std::vector<std::vector<int>> split_rooms(const World& world, const CorridorNetwork& network,
                                          const std::vector<StartSpot>& starts, Rng& rng);

// Waypoints of one robot: out of its start room, its rooms (visiting_order),
// then the rendezvous and its parking spot.
std::vector<Eigen::Vector2d> plan_route(const World& world, const CorridorNetwork& network, const StartSpot& start,
                                        const std::vector<int>& rooms_to_visit, const Eigen::Vector2d& parking_spot,
                                        Rng& rng);

}  // namespace sim_detail
}  // namespace dsswarm
