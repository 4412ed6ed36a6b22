#pragma once
// What the encounter engine's tests share (encounter_engine_test.cpp,
// encounter_order_test.cpp): a fake robot in the L-shaped office.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "protocol/encounter_engine.hpp"
#include "swarm/map_knowledge.hpp"
#include "swarm/test_scenes.hpp"

namespace dsswarm::protocol::engine_test {

// A robot reduced to what the engine asks of it: a map built in the L-shaped
// office from its own start, its scan where it stands, what it knows.
class FakeRobot : public AgentPort {
 public:
  FakeRobot(const std::string& name, const Pose2& start, const Pose2& now, std::uint64_t seed)
      : knowledge(name) {
    Rng rng(seed);
    const World world = test::l_shaped_office();
    std::vector<Pose2> path;
    for (int k = 0; k <= 10; ++k) path.push_back(interpolate(start, now, k / 10.0));
    own = std::make_shared<MultiResMap>(test::map_from(world, path, start, rng));
    view.map = own.get();
    view.points = test::scan_at(world, now, rng);
    view.pose = start.inverse() * now;
    view.surroundings = surroundings_points(*own, view.pose, 8.0, 2000);
    view.wide_surroundings = surroundings_points(*own, view.pose, 40.0, 8000);
  }
  std::optional<CapturedView> capture_view(const std::string&, std::uint64_t encounter) override {
    captured.push_back({encounter, merges});
    return CapturedView{view, 100.0, nullptr, nullptr, 0, nullptr};
  }
  MapSnapshot snapshot(const CapturedView&) override { return knowledge.snapshot(own, version); }
  std::vector<LayerVersion> inventory() const override {
    std::vector<LayerVersion> out{{knowledge.self(), version, 0}};
    for (const MapLayer& l : knowledge.layers()) out.push_back({l.origin, l.version, l.hops});
    return out;
  }
  std::optional<Pose2> known_frame(const std::string& origin) const override {
    const MapLayer* l = knowledge.find(origin);
    return l ? std::optional<Pose2>(l->origin_in_holder) : std::nullopt;
  }
  void merge(MapSnapshot snapshot, const Pose2& sender_in_self, const protocol::CapturedView&, std::uint64_t) override {
    if (snapshot.layers.empty()) return;  // the peer had nothing new
    ++merges;
    last_transform = sender_in_self;
    knowledge.absorb(snapshot, sender_in_self);
  }

  // Loop closing as the engine sees it: a revision, and its one submap at x = revision.
  std::uint64_t graph_revision() const override { return revision; }
  MapMoves map_moves(const std::string& /*peer*/, const std::vector<TieScan>& ties,
                     std::size_t /*max_closures*/) const override {
    MapMoves m{revision, {{1, Pose2(static_cast<double>(revision), 0.0, 0.0)}}, {}, {}};
    for (const TieScan& t : ties) m.ties.push_back({t.encounter, t.offered, t.offered * Pose2(0.1, 0.0, 0.0)});
    return m;
  }
  void follow(const std::string& peer, const MapMoves& moves) override { followed.emplace_back(peer, moves); }

  MapKnowledge knowledge;
  std::uint64_t version = 11;  // scans in its own map
  std::uint64_t revision = 0;
  std::vector<std::pair<std::string, MapMoves>> followed;
  std::shared_ptr<MultiResMap> own;
  EncounterView view;
  int merges = 0;
  Pose2 last_transform;
  std::vector<std::pair<std::uint64_t, int>> captured;  // (encounter, merges by then) per view taken
};

inline bool same(const Pose2& p, const Pose2& q) { return p.x == q.x && p.y == q.y && p.theta == q.theta; }

inline const Pose2 kStartA{1.5, 1.5, 0.4}, kStartB{8.5, 2.0, -2.5};

inline SwarmConfig unconfirmed() {
  SwarmConfig c;
  c.confirm = false;
  return c;
}

}  // namespace dsswarm::protocol::engine_test
