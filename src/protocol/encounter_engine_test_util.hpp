#pragma once
// What the encounter engine's tests share (encounter_engine_test.cpp,
// encounter_order_test.cpp): a fake robot in the L-shaped office.
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "protocol/encounter_engine.hpp"
#include "protocol/gate.hpp"
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

inline const Pose2 kStartA{1.5, 1.5, 0.4}, kStartB{8.5, 2.0, -2.5};

// Two robots' engines, a and b, talking through their gates.
struct Pair {
  Pair(const SwarmConfig& config)
      : a("a", kStartA, {3.0, 2.0, 0.1}, 1),
        b("b", kStartB, {5.0, 2.5, 2.9}, 2),
        ea("a", config, a),
        eb("b", config, b),
        ga("a"),
        gb("b") {}
  // Delivers everything in flight, `keep(bytes)` deciding what arrives.
  void pump(double now, const std::function<bool(const Outgoing&)>& keep = {}) {
    for (bool moved = true; moved;) {
      moved = false;
      for (auto [from, to, gate] : {std::tuple{&ea, &eb, &gb}, std::tuple{&eb, &ea, &ga}})
        for (const Outgoing& out : from->take_outbox()) {
          moved = true;
          if (keep && !keep(out)) continue;
          if (auto v = gate->admit(out.bytes); v.message) to->receive(*v.message, out.bytes.size(), now);
        }
    }
  }
  // Both robots told they are near (encounter `id` at `now`), everything
  // delivered; what each decided, A's first.
  std::pair<std::vector<EncounterOutcome>, std::vector<EncounterOutcome>> meet(std::uint64_t id, double now) {
    ea.start("b", id, now);
    eb.start("a", id, now);
    pump(now);
    return {ea.take_outcomes(), eb.take_outcomes()};
  }
  FakeRobot a, b;
  EncounterEngine ea, eb;
  MessageGate ga, gb;
};

inline SwarmConfig unconfirmed() {
  SwarmConfig c;
  c.confirm = false;
  return c;
}

}  // namespace dsswarm::protocol::engine_test
