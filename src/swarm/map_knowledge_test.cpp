#include "swarm/map_knowledge.hpp"

#include <gtest/gtest.h>

#include "swarm/map_merge.hpp"

namespace dsswarm {
namespace {

std::shared_ptr<const MultiResMap> map_with_cell(CellIndex c, float occupied) {
  auto m = std::make_shared<MultiResMap>();
  m->mutable_level(0).set(c, {occupied, 0.0f});
  return m;
}

MapSnapshot own_snapshot(const std::string& who, std::uint64_t version, CellIndex c) {
  return MapKnowledge(who).snapshot(map_with_cell(c, 0.5f), version);
}

void expect_same_layers(const MapKnowledge& x, const MapKnowledge& y) {
  const auto a = x.layers(), b = y.layers();
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].origin, b[i].origin);
    EXPECT_EQ(a[i].version, b[i].version);
    EXPECT_EQ(a[i].hops, b[i].hops);
    EXPECT_EQ(a[i].map, b[i].map);
    EXPECT_NEAR(a[i].origin_in_holder.x, b[i].origin_in_holder.x, 1e-12);
    EXPECT_NEAR(a[i].origin_in_holder.theta, b[i].origin_in_holder.theta, 1e-12);
  }
}

TEST(MapKnowledge, PiecesHeldMoveWhereTheirRobotSaysAndNothingElseDoes) {
  MapKnowledge a("a");
  auto piece = std::make_shared<const FrozenMap>(*map_with_cell({2, 2}, 0.5f));
  MapSnapshot from_b = own_snapshot("b", 7, {1, 1});
  from_b.layers[0].pieces = {{0, Pose2(), piece}, {1, Pose2(3.0, 0.0, 0.0), piece}};
  a.absorb(from_b, {1.0, 2.0, 0.5});
  EXPECT_FALSE(a.move_pieces("c", {{1, Pose2(3.5, 0.0, 0.0)}}));  // no layer of c
  EXPECT_FALSE(a.move_pieces("b", {{1, Pose2(3.0, 0.0, 0.0)}}));  // where it was
  EXPECT_FALSE(a.move_pieces("b", {{9, Pose2(1.0, 0.0, 0.0)}}));  // a piece not held
  EXPECT_TRUE(a.move_pieces("b", {{1, Pose2(3.5, 0.2, 0.1)}, {9, Pose2(1.0, 0.0, 0.0)}}));
  const MapLayer& b = *a.find("b");
  ASSERT_EQ(b.pieces.size(), 2u);
  EXPECT_EQ(b.pieces[0].pose.x, 0.0);
  EXPECT_EQ(b.pieces[1].pose.x, 3.5);
  EXPECT_EQ(b.pieces[1].pose.theta, 0.1);
  EXPECT_EQ(b.pieces[1].map, piece);  // the evidence stays
  EXPECT_EQ(b.version, 7u);
  EXPECT_EQ(b.origin_in_holder.x, 1.0);  // its frame is placed by the holder, not moved
}

TEST(MapKnowledge, SameSnapshotTwiceEqualsOnce) {
  MapKnowledge a("a");
  const MapSnapshot from_b = own_snapshot("b", 7, {1, 1});
  EXPECT_TRUE(a.absorb(from_b, {1.0, 2.0, 0.5}));
  const MapKnowledge once = a;
  EXPECT_FALSE(a.absorb(from_b, {1.0, 2.0, 0.5}));
  expect_same_layers(a, once);
  // The working map is the same too: the evidence is not counted twice.
  const MultiResMap own;
  const MultiResMap w1 = compose_working_map(own, once.layers());
  const MultiResMap w2 = compose_working_map(own, a.layers());
  EXPECT_EQ(w1.finest().tiles_allocated(), w2.finest().tiles_allocated());
}

TEST(MapKnowledge, MergeOrderDoesNotMatter) {
  const MapSnapshot b1 = own_snapshot("b", 5, {1, 1});
  const MapSnapshot b2 = own_snapshot("b", 9, {2, 2});  // b later: its map grew
  const MapSnapshot c1 = own_snapshot("c", 3, {3, 3});
  const Pose2 tb{1, 0, 0.1}, tc{0, 4, -2.0};
  MapKnowledge x("a"), y("a"), z("a");
  x.absorb(b1, tb), x.absorb(b2, tb), x.absorb(c1, tc);
  y.absorb(c1, tc), y.absorb(b2, tb), y.absorb(b1, tb);
  z.absorb(b2, tb), z.absorb(c1, tc), z.absorb(b1, tb);
  expect_same_layers(x, y);
  expect_same_layers(x, z);
  EXPECT_EQ(x.find("b")->version, 9u);  // the newer map of b wins whatever the order
}

TEST(MapKnowledge, KnowledgeSpreadsThroughTheChainOfTransforms) {
  // b met c; then a meets b: a learns c's map, placed through b.
  MapKnowledge b("b");
  const Pose2 c_in_b{2.0, -1.0, 0.7}, b_in_a{-3.0, 0.5, -1.1};
  b.absorb(own_snapshot("c", 4, {0, 0}), c_in_b);
  MapKnowledge a("a");
  a.absorb(b.snapshot(map_with_cell({5, 5}, 0.4f), 11), b_in_a);
  ASSERT_NE(a.find("c"), nullptr);
  const Pose2 expected = b_in_a * c_in_b;
  EXPECT_NEAR(a.find("c")->origin_in_holder.x, expected.x, 1e-12);
  EXPECT_NEAR(a.find("c")->origin_in_holder.y, expected.y, 1e-12);
  EXPECT_NEAR(a.find("c")->origin_in_holder.theta, expected.theta, 1e-12);
  EXPECT_EQ(a.find("c")->hops, 2);
  EXPECT_EQ(a.find("b")->hops, 1);
  EXPECT_EQ(a.find("b")->version, 11u);
}

TEST(MapKnowledge, OwnEvidenceNeverComesBack) {
  // a's map, passed on by b, must not be merged into a again.
  MapKnowledge b("b");
  b.absorb(own_snapshot("a", 20, {0, 0}), {1, 1, 0});
  MapKnowledge a("a");
  a.absorb(b.snapshot(map_with_cell({1, 1}, 0.3f), 2), {-1, -1, 0});
  EXPECT_EQ(a.find("a"), nullptr);
  EXPECT_EQ(a.size(), 1u);
}

TEST(MapKnowledge, SnapshotPutsOwnMapFirst) {
  MapKnowledge a("a");
  a.absorb(own_snapshot("b", 1, {0, 0}), {});
  const MapSnapshot s = a.snapshot(map_with_cell({0, 0}, 0.2f), 42);
  ASSERT_EQ(s.layers.size(), 2u);
  EXPECT_EQ(s.sender, "a");
  EXPECT_EQ(s.layers[0].origin, "a");
  EXPECT_EQ(s.layers[0].version, 42u);
  EXPECT_EQ(s.layers[0].hops, 0);
  EXPECT_EQ(s.layers[1].origin, "b");
}

}  // namespace
}  // namespace dsswarm
