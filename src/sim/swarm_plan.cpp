#include "sim/swarm_plan.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/errors.hpp"
#include "common/rng.hpp"

namespace dsswarm::sim_detail {
namespace {

// m between start spots and from the parking spots (the error message in pick_starts says 3 m)
constexpr double kMinStartSeparation = 3.0;
constexpr double kParkingSpacing = 1.0;      // m between neighbouring parking spots
constexpr double kParkingClearance = 0.4;    // m from walls, as every tour leg keeps
// Start spots in a room lie on the door axis between inside_door and
// safe_spot (free of clutter by construction), at least this far along it.
constexpr double kStartMinAlongLane = 0.3;
constexpr double kCorridorStartSpacing = 6.0;  // m of corridor per candidate start spot
constexpr double kCorridorEndMargin = 1.0;     // m: corridor start spots keep off the corridor ends
constexpr double kStartClearance = 0.45;

std::size_t random_index(Rng& rng, std::size_t n) {
  return std::min(n - 1, static_cast<std::size_t>(rng.uniform() * static_cast<double>(n)));
}

template <typename T>
void shuffle(std::vector<T>& items, Rng& rng) {  // Fisher-Yates (std::shuffle is not portable)
  for (std::size_t i = items.size(); i > 1; --i) std::swap(items[i - 1], items[random_index(rng, i)]);
}

}  // namespace

std::vector<Eigen::Vector2d> parking_spots(const World& world, const Eigen::Vector2d& centre, int robots) {
  const int reach = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(robots)))) + 3;
  struct Candidate {
    int i, j;
    Eigen::Vector2d position;
  };
  std::vector<Candidate> candidates;
  for (int i = -reach; i <= reach; ++i)
    for (int j = -reach; j <= reach; ++j) {
      const Eigen::Vector2d p = centre + kParkingSpacing * Eigen::Vector2d(i, j);
      if (world.is_segment_free(centre, p, kParkingClearance)) candidates.push_back({i, j, p});
    }
  // Integer keys keep the order exact (no floating-point ties).
  std::stable_sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    return a.i * a.i + a.j * a.j < b.i * b.i + b.j * b.j;
  });
  require_config("swarm config", static_cast<int>(candidates.size()) >= robots,
          "robots: only " + std::to_string(candidates.size()) + " parking spots fit around the rendezvous for " +
              std::to_string(robots) + " robots; use a larger building (swarm_world_config)");
  std::vector<Eigen::Vector2d> spots;
  for (int r = 0; r < robots; ++r) spots.push_back(candidates[static_cast<std::size_t>(r)].position);
  return spots;
}

std::vector<StartSpot> pick_starts(const World& world, const CorridorNetwork& network,
                                   const std::vector<Eigen::Vector2d>& parking, int robots, Rng& rng) {
  const BuildingLayout& layout = world.layout();
  std::vector<StartSpot> candidates;
  for (std::size_t k = 0; k < layout.rooms.size(); ++k) {
    const Room& room = layout.rooms[k];
    const double along = rng.uniform(kStartMinAlongLane, 1.0);
    candidates.push_back(
        {room.inside_door + along * (room.safe_spot - room.inside_door), static_cast<int>(k), room.corridor});
  }
  for (std::size_t c = 0; c < layout.corridors.size(); ++c) {
    const int ci = static_cast<int>(c);
    const double length = network.length(ci);
    if (length <= 2 * kCorridorEndMargin) continue;
    const int n = std::max(1, static_cast<int>(length / kCorridorStartSpacing));
    for (int k = 0; k < n; ++k)
      candidates.push_back(
          {network.point({ci, rng.uniform(kCorridorEndMargin, length - kCorridorEndMargin)}), -1, ci});
  }
  shuffle(candidates, rng);

  auto far_from = [](const Eigen::Vector2d& p, const auto& others, auto position_of) {
    return std::all_of(others.begin(), others.end(),
                       [&](const auto& o) { return (position_of(o) - p).norm() >= kMinStartSeparation; });
  };
  std::vector<StartSpot> starts;
  for (const StartSpot& candidate : candidates) {
    if (static_cast<int>(starts.size()) == robots) break;
    if (!world.is_free(candidate.position, kStartClearance)) continue;
    if (!far_from(candidate.position, parking, [](const Eigen::Vector2d& q) { return q; })) continue;
    if (!far_from(candidate.position, starts, [](const StartSpot& s) { return s.position; })) continue;
    starts.push_back(candidate);
  }
  require_config("swarm config", static_cast<int>(starts.size()) == robots,
          "robots: the building has room for only " + std::to_string(starts.size()) +
              " start spots 3 m apart (and away from the rendezvous), not " + std::to_string(robots) +
              "; use a larger building (swarm_world_config)");
  return starts;
}

std::vector<std::vector<int>> split_rooms(const World& world, const CorridorNetwork& network,
                                          const std::vector<StartSpot>& starts, Rng& rng) {
  const auto& rooms = world.layout().rooms;
  const std::size_t robots = starts.size();
  const std::size_t corridors = world.layout().corridors.size();
  // Home corridors: as many robots per corridor as possible (robot j of a
  // random order gets slot corridor j % corridors), each robot preferably
  // at home where it starts, so that nobody crosses the building needlessly.
  std::vector<std::size_t> order(robots);
  for (std::size_t r = 0; r < robots; ++r) order[r] = r;
  shuffle(order, rng);
  std::vector<std::size_t> free_slots(corridors, 0);
  for (std::size_t j = 0; j < robots; ++j) ++free_slots[j % corridors];
  std::vector<std::size_t> home(robots, corridors);
  for (std::size_t r : order) {
    const auto c = static_cast<std::size_t>(starts[r].corridor);
    if (free_slots[c] > 0) {
      --free_slots[c];
      home[r] = c;
    }
  }
  for (std::size_t r : order)
    for (std::size_t c = 0; c < corridors && home[r] == corridors; ++c)
      if (free_slots[c] > 0) {
        --free_slots[c];
        home[r] = c;
      }

  std::vector<std::vector<int>> shares(robots);
  for (std::size_t c = 0; c < corridors; ++c) {
    std::vector<std::size_t> at_home;  // in the random order
    for (std::size_t r : order)
      if (home[r] == c) at_home.push_back(r);
    if (at_home.empty()) at_home = order;  // fewer robots than corridors: everyone shares this one

    std::vector<int> along;
    for (std::size_t k = 0; k < rooms.size(); ++k)
      if (rooms[k].corridor == static_cast<int>(c)) along.push_back(static_cast<int>(k));
    auto position = [&](int k) {
      const Room& room = rooms[static_cast<std::size_t>(k)];
      return network.project(room.corridor, room.door).s;
    };
    std::stable_sort(along.begin(), along.end(), [&](int x, int y) { return position(x) < position(y); });
    const std::size_t offset = random_index(rng, at_home.size());
    for (std::size_t i = 0; i < along.size(); ++i) shares[at_home[(i + offset) % at_home.size()]].push_back(along[i]);
  }

  std::vector<std::vector<int>> visits(robots);
  for (std::size_t r = 0; r < robots; ++r) {
    std::vector<int> others, others_at_home;
    for (std::size_t k = 0; k < rooms.size(); ++k) {
      const int room = static_cast<int>(k);
      if (room == starts[r].room) continue;
      if (std::find(shares[r].begin(), shares[r].end(), room) != shares[r].end()) {
        visits[r].push_back(room);
      } else {
        others.push_back(room);
        if (static_cast<std::size_t>(rooms[k].corridor) == home[r]) others_at_home.push_back(room);
      }
    }
    // The extra room from the home corridor: one more from far away would
    // make the slowest robot (and so everyone's log) much longer.
    const std::vector<int>& pool = others_at_home.empty() ? others : others_at_home;
    if (!pool.empty()) visits[r].push_back(pool[random_index(rng, pool.size())]);
  }
  return visits;
}

namespace {

// The order a robot visits its rooms in on its way to the rendezvous (the
// first corridor's begin): corridor by corridor, along each one out to the
// farthest room and then room by room back towards the begin end (the
// shortest sweep that ends there), with the corridors in the order that
// makes the whole trip shortest. Robots that start at different places thus
// drive the shared corridors in both directions at different times, and
// meet on the way.
std::vector<int> visiting_order(const World& world, const CorridorNetwork& network, const NetworkPoint& start,
                                const std::vector<int>& rooms_to_visit) {
  constexpr std::size_t kMaxCorridorsToPermute = 6;  // 720 orders; beyond, by index
  const auto& rooms = world.layout().rooms;
  auto front_of = [&](int k) {
    const Room& room = rooms[static_cast<std::size_t>(k)];
    return network.project(room.corridor, room.door);
  };
  std::vector<int> corridors;
  for (int k : rooms_to_visit) corridors.push_back(front_of(k).corridor);
  std::sort(corridors.begin(), corridors.end());
  corridors.erase(std::unique(corridors.begin(), corridors.end()), corridors.end());

  auto order_for = [&](const std::vector<int>& corridor_order) {
    std::vector<int> order;
    for (int c : corridor_order) {
      const std::size_t first = order.size();
      for (int k : rooms_to_visit)
        if (front_of(k).corridor == c) order.push_back(k);
      std::stable_sort(order.begin() + static_cast<std::ptrdiff_t>(first), order.end(),
                       [&](int a, int b) { return front_of(a).s > front_of(b).s; });
    }
    return order;
  };
  auto trip_length = [&](const std::vector<int>& order) {
    double length = 0;
    NetworkPoint at = start;
    for (int k : order) {
      length += network.distance(at, front_of(k));
      at = front_of(k);
    }
    return length + network.distance(at, {0, 0.0});
  };
  std::vector<int> best = order_for(corridors);
  if (corridors.size() <= kMaxCorridorsToPermute) {
    double best_length = trip_length(best);
    while (std::next_permutation(corridors.begin(), corridors.end())) {
      std::vector<int> candidate = order_for(corridors);
      const double length = trip_length(candidate);
      if (length < best_length - 1e-9) {
        best = std::move(candidate);
        best_length = length;
      }
    }
  }
  return best;
}

}  // namespace

std::vector<Eigen::Vector2d> plan_route(const World& world, const CorridorNetwork& network, const StartSpot& start,
                                        const std::vector<int>& rooms_to_visit, const Eigen::Vector2d& parking_spot,
                                        Rng& rng) {
  const auto& rooms = world.layout().rooms;
  std::vector<Eigen::Vector2d> route;
  auto go = [&](const Eigen::Vector2d& p) {
    const Eigen::Vector2d& last = route.empty() ? start.position : route.back();
    if ((last - p).norm() > 1e-6) route.push_back(p);
  };
  auto front_of = [&](const Room& room) { return network.project(room.corridor, room.door); };

  NetworkPoint at = network.project(start.corridor, start.position);
  if (start.room >= 0) {
    const Room& room = rooms[static_cast<std::size_t>(start.room)];
    go(room.inside_door);
    at = front_of(room);
    go(network.point(at));
  }
  for (int k : visiting_order(world, network, at, rooms_to_visit)) {
    const Room& room = rooms[static_cast<std::size_t>(k)];
    const NetworkPoint front = front_of(room);
    network.route(at, front, go);
    go(room.inside_door);
    go(pick_room_spot(world, room, rng));
    go(room.inside_door);
    go(network.point(front));
    at = front;
  }
  // To the parking spot from the nearest point of the first corridor (no
  // detour through the rendezvous centre), or through the centre, from which
  // every spot is reachable in a straight line.
  const NetworkPoint beside_spot = network.project(0, parking_spot);
  const bool direct = world.is_segment_free(network.point(beside_spot), parking_spot, kParkingClearance);
  network.route(at, direct ? beside_spot : NetworkPoint{0, 0.0}, go);
  go(parking_spot);
  return route;
}

}  // namespace dsswarm::sim_detail
