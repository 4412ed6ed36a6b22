#include "protocol/wire.hpp"

#include <gtest/gtest.h>
#include <zlib.h>

#include <cmath>
#include <limits>

namespace dsswarm::protocol {
namespace {

Message with(Body body, std::string recipient = "robot2") {
  return Message{Header{"robot1", std::move(recipient), 1234567, 42}, std::move(body)};
}

Offer sample_offer() {
  Offer o;
  o.encounter = 7;
  o.stamp = 976052000.125;
  o.pose = {1.5, -2.0, 0.3};
  o.points = {{1.0f, 2.0f, 1.5f}, {-0.5f, 3.25f, 1.0f}};
  o.surroundings = {{4.0f, 4.0f, 1.0f}};
  o.wide_surroundings = {};
  o.inventory = {{"robot1", 120, 0}, {"robot3", 40, 2}};
  return o;
}

Placement sample_placement() {
  Placement p;
  p.encounter = 7;
  p.placement.valid = true;
  p.placement.located.best = {{2.0, 1.0, -0.2}, 0.8, 0.6, 0.9, 0.95, 0.85};
  p.placement.located.runner_up = PoseHypothesis{{5.0, 1.0, 2.0}, 0.5, 0.2, 0.4, 0.9, 0.3};
  p.placement.located.evaluations = 9000;
  p.placement.wide = Pose2{2.01, 1.0, -0.21};
  p.known_transform = Pose2{0.1, 0.2, 0.3};
  p.pending = {{1.0, 2.0, 3.0}};
  p.compute_ms = 321.5;
  return p;
}

Moved sample_moved() {
  Moved m;
  m.moves.revision = 17;
  m.moves.pieces = {{0, {0.0, 0.0, 0.0}}, {3, {12.5, -4.0, 1.25}}};
  m.moves.ties = {{7, {1.5, -2.0, 0.3}, {1.6, -2.1, 0.31}}};
  m.moves.closures = {{4, {2.0, 1.0, 0.5}, {-3.0, 7.5, -1.0}}};
  return m;
}

// Re-seals a message whose bytes a test altered, so that only the change is wrong.
void reseal(std::vector<std::uint8_t>& bytes) {
  const auto crc = static_cast<std::uint32_t>(crc32_z(0, bytes.data(), bytes.size() - 4));
  for (int i = 0; i < 4; ++i) bytes[bytes.size() - 4 + i] = static_cast<std::uint8_t>(crc >> (8 * i));
}

std::string error_of(const std::vector<std::uint8_t>& bytes, const WireLimits& limits = {}) {
  try {
    decode(bytes, limits);
  } catch (const ProtocolError& e) {
    return e.what();
  }
  return "";
}

TEST(Wire, EveryKindRoundTrips) {
  AgentStatus s{12.5, 100, 90, 10, 9.5, 2, 3, 1, 4.5, 88, 6};
  Proximity near{"robot1", "robot2", 99, 976052000.5, std::numeric_limits<double>::quiet_NaN()};
  Chunk c{7, 1, 3, 150000, 0xdeadbeef, std::vector<std::uint8_t>(1000, 0xab)};
  const std::vector<Body> bodies{Heartbeat{s}, near, sample_offer(), Decline{7, "no scan yet"}, sample_placement(), c,
                                 sample_moved()};
  for (const Body& body : bodies) {
    const Message in = with(body);
    const Message out = decode(encode(in));
    EXPECT_EQ(kind_of(out.body), kind_of(in.body));
    EXPECT_EQ(out.header.sender, "robot1");
    EXPECT_EQ(out.header.recipient, "robot2");
    EXPECT_EQ(out.header.incarnation, 1234567u);
    EXPECT_EQ(out.header.sequence, 42u);
    EXPECT_EQ(encode(out), encode(in)) << kind_name(kind_of(in.body));  // every field survived
  }
  const Offer o = std::get<Offer>(decode(encode(with(sample_offer()))).body);
  EXPECT_EQ(o.inventory, sample_offer().inventory);
  EXPECT_FLOAT_EQ(o.points[1].y, 3.25f);
  const Placement p = std::get<Placement>(decode(encode(with(sample_placement()))).body);
  ASSERT_TRUE(p.placement.located.runner_up);
  EXPECT_DOUBLE_EQ(p.placement.located.runner_up->surroundings_score, 0.2);
  EXPECT_TRUE(std::isnan(std::get<Proximity>(decode(encode(with(near))).body).b_stamp));
  const MapMoves m = std::get<Moved>(decode(encode(with(sample_moved()))).body).moves;
  ASSERT_EQ(m.pieces.size(), 2u);
  EXPECT_EQ(m.pieces[1].id, 3);
  EXPECT_DOUBLE_EQ(m.ties[0].now.theta, 0.31);
  ASSERT_EQ(m.closures.size(), 1u);
  EXPECT_EQ(m.closures[0].submap, 4);
  EXPECT_DOUBLE_EQ(m.closures[0].in_cells.theta, 0.5);
  EXPECT_DOUBLE_EQ(m.closures[0].node.y, 7.5);
}

// Cuts `n` bytes from the end of a message's body, and its body size to match.
std::vector<std::uint8_t> without_body_tail(std::vector<std::uint8_t> bytes, std::size_t n) {
  const auto u32_at = [&](std::size_t o) {
    return static_cast<std::uint32_t>(bytes[o] | bytes[o + 1] << 8 | bytes[o + 2] << 16 | bytes[o + 3] << 24);
  };
  std::size_t at = 0;  // the body size: the only field saying how many bytes follow it (less the checksum)
  while (at + 8 <= bytes.size() && u32_at(at) != bytes.size() - 4 - (at + 4)) ++at;
  EXPECT_LT(at + 8, bytes.size());
  const std::uint32_t shorter = u32_at(at) - static_cast<std::uint32_t>(n);
  for (std::size_t i = 0; i < 4; ++i) bytes[at + i] = static_cast<std::uint8_t>(shorter >> (8 * i));
  bytes.erase(bytes.end() - 4 - static_cast<std::ptrdiff_t>(n), bytes.end() - 4);
  reseal(bytes);
  return bytes;
}

// A Moved from an agent before loop closures travelled ends after its ties:
// it is read as carrying none. Cut inside the closures, it is refused.
TEST(Wire, AMovedWithoutClosuresIsReadAsHavingNone) {
  Moved older = sample_moved();
  older.moves.closures.clear();
  const MapMoves m = std::get<Moved>(decode(without_body_tail(encode(with(older)), 4)).body).moves;
  EXPECT_TRUE(m.closures.empty());
  ASSERT_EQ(m.ties.size(), 1u);
  EXPECT_DOUBLE_EQ(m.ties[0].now.theta, 0.31);
  EXPECT_NE(error_of(without_body_tail(encode(with(sample_moved())), 8)).find("closure"), std::string::npos);
}

TEST(Wire, DamagedOrForeignBytesAreRefusedWithTheReason) {
  const std::vector<std::uint8_t> good = encode(with(sample_offer()));
  EXPECT_NE(error_of({}).find("shorter"), std::string::npos);
  for (std::size_t n : {std::size_t{10}, good.size() / 2, good.size() - 1}) {
    const std::vector<std::uint8_t> cut(good.begin(), good.begin() + static_cast<std::ptrdiff_t>(n));
    EXPECT_FALSE(error_of(cut).empty()) << n;
  }
  auto flipped = good;
  flipped[good.size() / 2] ^= 0x10;
  EXPECT_NE(error_of(flipped).find("checksum"), std::string::npos);
  auto magic = good;
  magic[0] = 'X';
  EXPECT_NE(error_of(magic).find("magic"), std::string::npos);
  auto version = good;
  version[4] = 9;
  reseal(version);
  EXPECT_NE(error_of(version).find("protocol version 9"), std::string::npos);
  auto kind = good;
  kind[6] = 77;
  reseal(kind);
  EXPECT_NE(error_of(kind).find("kind 77"), std::string::npos);
  auto trailing = good;
  trailing.insert(trailing.end() - 4, 0);
  reseal(trailing);
  EXPECT_NE(error_of(trailing).find("body size"), std::string::npos);
  WireLimits small;
  small.max_message_bytes = 100;
  EXPECT_NE(error_of(good, small).find("exceeds"), std::string::npos);
}

TEST(Wire, NonsenseValuesAreRefusedBeforeUse) {
  Offer nan_pose = sample_offer();
  nan_pose.pose.x = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(error_of(encode(with(nan_pose))).find("pose is not finite"), std::string::npos);
  Offer inf_point = sample_offer();
  inf_point.points[0].x = std::numeric_limits<float>::infinity();
  EXPECT_NE(error_of(encode(with(inf_point))).find("not finite"), std::string::npos);
  Offer far_pose = sample_offer();
  far_pose.pose.y = 3e9;
  EXPECT_NE(error_of(encode(with(far_pose))).find("more than 1000000 m from its frame's origin"), std::string::npos);
  Offer far_point = sample_offer();
  far_point.surroundings[0].y = -1e30f;
  EXPECT_NE(error_of(encode(with(far_point))).find("more than 1000 m from the robot"), std::string::npos);
  Offer many = sample_offer();
  many.points.assign(30000, ScanPoint{});
  EXPECT_NE(error_of(encode(with(many))).find("at most 20000"), std::string::npos);
  Offer bad_origin = sample_offer();
  bad_origin.inventory[0].origin = "../etc";
  EXPECT_NE(error_of(encode(with(bad_origin))).find("not a valid agent name"), std::string::npos);
  Placement ratio = sample_placement();
  ratio.placement.located.best.inlier_ratio = 1.5;
  EXPECT_NE(error_of(encode(with(ratio))).find("inlier ratio"), std::string::npos);
  Chunk out_of_range{7, 3, 3, 100, 0, {1, 2, 3}};
  EXPECT_NE(error_of(encode(with(out_of_range))).find("out of range"), std::string::npos);
  Chunk too_big{7, 0, 1, std::uint64_t{1} << 40, 0, {1}};
  EXPECT_NE(error_of(encode(with(too_big))).find("at most"), std::string::npos);
  EXPECT_NE(error_of(encode(with(Proximity{"robot1", "robot1", 1}))).find("twice"), std::string::npos);
  Moved twice = sample_moved();
  twice.moves.pieces[1].id = 0;
  EXPECT_NE(error_of(encode(with(twice))).find("submap 0 is listed twice"), std::string::npos);
  Moved inf_tie = sample_moved();
  inf_tie.moves.ties[0].now.theta = std::numeric_limits<double>::infinity();
  EXPECT_NE(error_of(encode(with(inf_tie))).find("encounter pose now is not finite"), std::string::npos);
  WireLimits few;
  few.max_pieces = 1;
  EXPECT_NE(error_of(encode(with(sample_moved())), few).find("submap poses: 2 entries, at most 1"), std::string::npos);
  Message bad_sender = with(Decline{1, "x"});
  bad_sender.header.sender = "a b";
  EXPECT_NE(error_of(encode(bad_sender)).find("sender"), std::string::npos);
}

TEST(Wire, LengthFieldsCannotMakeTheReaderAllocateOrOverrun) {
  // A point count that claims more points than the bytes left is refused
  // before anything is allocated.
  std::vector<std::uint8_t> bytes = encode(with(sample_offer()));
  // The offer's point count follows u64 id, f64 stamp and three f64 pose
  // fields at the start of the body.
  const std::size_t body = 4 + 2 + 1 + (4 + 6) + (4 + 6) + 8 + 8 + 4;
  const std::size_t count_at = body + 8 + 8 + 24;
  ASSERT_EQ(bytes[count_at], 2);  // two points
  bytes[count_at] = 0xff;
  bytes[count_at + 1] = 0x0f;
  reseal(bytes);
  EXPECT_NE(error_of(bytes).find("cannot fit"), std::string::npos);
}

}  // namespace
}  // namespace dsswarm::protocol
