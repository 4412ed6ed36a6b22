#include "io/maps/dsmap.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "common/errors.hpp"
#include "common/test_files.hpp"
#include "sensor/scan_points.hpp"
#include "io/maps/dsmap_test_util.hpp"
#include "sim/scenario.hpp"

namespace dsswarm {
namespace {

using Bytes = std::vector<std::uint8_t>;
using namespace dsmap_test;

// Every cell of `b` within one quantization step of `a`, in both directions
// (cells absent from one grid are vacuous there), and every decoded mass valid.
void expect_same_cells(const DsGrid& a, const DsGrid& b, const std::string& where) {
  constexpr float kStep = 1.0f / 65535.0f + 1e-7f;
  int bad = 0;
  auto compare = [&](const DsGrid& from, const DsGrid& to) {
    from.for_each_tile([&](CellIndex origin, const PackedMass* cells) {
      for (int i = 0; i < DsGrid::kTileCells; ++i) {
        const CellIndex c{origin.x + (i % DsGrid::kTileSize), origin.y + (i / DsGrid::kTileSize)};
        const DsMass m = to.at(c);
        if (std::abs(cells[i].mass().occupied - m.occupied) > kStep || std::abs(cells[i].mass().free - m.free) > kStep ||
            m.unknown() < 0.0f || cells[i].mass().unknown() < 0.0f)
          if (++bad <= 3)
            ADD_FAILURE() << where << " cell (" << c.x << ", " << c.y << "): " << cells[i].mass().occupied << "/"
                          << cells[i].mass().free << " vs " << m.occupied << "/" << m.free;
      }
    });
  };
  compare(a, b);
  compare(b, a);
  EXPECT_EQ(bad, 0) << where;
}

void expect_same_snapshot(const MapSnapshot& a, const MapSnapshot& b) {
  EXPECT_EQ(a.sender, b.sender);
  ASSERT_EQ(a.layers.size(), b.layers.size());
  for (std::size_t i = 0; i < a.layers.size(); ++i) {
    const MapLayer &x = a.layers[i], &y = b.layers[i];
    EXPECT_EQ(x.origin, y.origin);
    EXPECT_EQ(x.version, y.version);
    EXPECT_EQ(x.hops, y.hops);
    EXPECT_EQ(x.origin_in_holder.x, y.origin_in_holder.x);
    EXPECT_EQ(x.origin_in_holder.y, y.origin_in_holder.y);
    EXPECT_EQ(x.origin_in_holder.theta, y.origin_in_holder.theta);
    const MapConfig &cx = x.map->config(), &cy = y.map->config();
    EXPECT_EQ(cx.resolution, cy.resolution);
    EXPECT_EQ(cx.levels, cy.levels);
    EXPECT_EQ(cx.evidence.hit_occupied, cy.evidence.hit_occupied);
    EXPECT_EQ(cx.evidence.pass_free, cy.evidence.pass_free);
    EXPECT_EQ(cx.evidence.min_unknown, cy.evidence.min_unknown);
    ASSERT_EQ(x.map->levels(), y.map->levels());
    for (int l = 0; l < x.map->levels(); ++l) {
      EXPECT_DOUBLE_EQ(x.map->level(l).resolution(), y.map->level(l).resolution());
      expect_same_cells(x.map->level(l), y.map->level(l), "layer " + std::to_string(i) + " level " + std::to_string(l));
    }
  }
}
TEST(Dsmap, RoundTripKeepsCellsConfigAndLayers) {
  const MapSnapshot s = two_layer_snapshot();
  const Bytes bytes = encode_dsmap(s);
  const MapSnapshot back = decode_dsmap(bytes, "mem");
  expect_same_snapshot(s, back);
  EXPECT_EQ(encode_dsmap(back), bytes);  // deterministic, and quantization is idempotent
}

TEST(Dsmap, EmptySnapshotAndEmptyMapRoundTrip) {
  MapSnapshot empty;
  empty.sender = "nobody";
  const MapSnapshot back = decode_dsmap(encode_dsmap(empty), "mem");
  EXPECT_EQ(back.sender, "nobody");
  EXPECT_TRUE(back.layers.empty());

  MapSnapshot blank;
  blank.layers.push_back({"r", 0, Pose2(), 0, std::make_shared<MultiResMap>(), {}});
  const MapSnapshot blank_back = decode_dsmap(encode_dsmap(blank), "mem");
  ASSERT_EQ(blank_back.layers.size(), 1u);
  EXPECT_EQ(blank_back.layers[0].map->cells_allocated(), 0u);
}

TEST(Dsmap, SkipsVacuousTilesAndKeepsMassesValid) {
  auto map = std::make_shared<MultiResMap>(MapConfig{0.05, 1, {}, false, false});
  DsGrid& g = map->mutable_level(0);
  g.set({1000, 1000}, DsMass::vacuous());                   // allocated, vacuous: not stored
  g.set({0, 0}, DsMass{0.7f, 0.3f});                        // no unknown mass at all
  g.set({1, 0}, DsMass{0.33333334f, 0.66666666f});          // rounds up on both
  g.set({2, 0}, DsMass{1.0f, 0.0f});
  MapSnapshot s;
  s.layers.push_back({"r", 1, Pose2(), 0, map, {}});
  const MapSnapshot back = decode_dsmap(encode_dsmap(s), "mem");
  const DsGrid& b = back.layers[0].map->level(0);
  EXPECT_EQ(b.tiles_allocated(), 1u);
  for (int x = 0; x < 3; ++x) {
    EXPECT_GE(b.at({x, 0}).unknown(), 0.0f) << x;
    EXPECT_NEAR(b.at({x, 0}).occupied, g.at({x, 0}).occupied, 1.0 / 65535) << x;
    EXPECT_NEAR(b.at({x, 0}).free, g.at({x, 0}).free, 1.0 / 65535 + 1e-7) << x;
  }
}

TEST(Dsmap, EncodeRefusesInconsistentLayers) {
  MapSnapshot s = two_layer_snapshot();
  s.layers[1].map = std::make_shared<MultiResMap>(MapConfig{0.1, 3, {}, false, false});
  EXPECT_THROW(encode_dsmap(s), std::invalid_argument);
  s.layers[1].map = nullptr;
  EXPECT_THROW(encode_dsmap(s), std::invalid_argument);
}

TEST(Dsmap, FileRoundTripAndMissingFile) {
  const auto dir = test::fresh_dir("dsmap");
  const MapSnapshot s = two_layer_snapshot();
  write_dsmap((dir / "a.dsmap").string(), s);
  expect_same_snapshot(s, read_dsmap((dir / "a.dsmap").string()));
  try {
    read_dsmap((dir / "none.dsmap").string());
    FAIL() << "missing file accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("none.dsmap"), std::string::npos) << e.what();
  }
  EXPECT_THROW(read_dsmap(dir.string()), InputError);  // a directory
}

MapSnapshot snapshot_with_pieces() {
  MapSnapshot s = two_layer_snapshot();
  const MapConfig config = s.layers.front().map->config();
  MultiResMap piece(config);
  piece.insert_scan(Pose2(0.2, -0.1, 0.4), Pose2(), room_scan(Pose2(0.2, -0.1, 0.4)));
  s.layers.front().pieces.push_back({3, Pose2(1.5, -0.25, 0.75), std::make_shared<const FrozenMap>(piece)});
  s.layers.back().pieces.push_back({0, Pose2(), std::make_shared<const FrozenMap>(*room_map(config))});
  s.layers.back().pieces.push_back({-7, Pose2(-4.0, 2.0, -3.0), std::make_shared<const FrozenMap>(piece)});
  return s;
}

TEST(Dsmap, SubmapPiecesRoundTripWithTheirIdsPosesAndCells) {
  const MapSnapshot s = snapshot_with_pieces();
  const Bytes bytes = encode_dsmap(s);
  const MapSnapshot back = decode_dsmap(bytes, "mem");
  expect_same_snapshot(s, back);
  const MapConfig config = s.layers.front().map->config();
  for (std::size_t i = 0; i < s.layers.size(); ++i) {
    ASSERT_EQ(back.layers[i].pieces.size(), s.layers[i].pieces.size());
    for (std::size_t k = 0; k < s.layers[i].pieces.size(); ++k) {
      const MapPiece& x = s.layers[i].pieces[k];
      const MapPiece& y = back.layers[i].pieces[k];
      EXPECT_EQ(y.id, x.id);
      EXPECT_EQ(y.pose.x, x.pose.x);
      EXPECT_EQ(y.pose.y, x.pose.y);
      EXPECT_EQ(y.pose.theta, x.pose.theta);
      const MultiResMap a = x.map->thaw(config), b = y.map->thaw(config);
      for (int l = 0; l < config.levels; ++l)
        expect_same_cells(a.level(l), b.level(l), "piece " + std::to_string(k) + " level " + std::to_string(l));
    }
  }
  EXPECT_EQ(encode_dsmap(back), bytes);  // frozen -> 16 bits -> frozen gives the same bytes
}

TEST(Dsmap, Version1FilesAreStillRead) {
  const MapSnapshot s = two_layer_snapshot();
  const MapSnapshot back = decode_dsmap(encode_dsmap(s, 1), "old.dsmap");
  expect_same_snapshot(s, back);
  for (const MapLayer& l : back.layers) EXPECT_TRUE(l.pieces.empty());
  EXPECT_THROW(encode_dsmap(snapshot_with_pieces(), 1), std::invalid_argument);  // version 1 has no place for them
}

TEST(Dsmap, RealisticMapSizeAndRoundTrip) {
  const SimulatedRun sim = simulate_demo(DemoConfig{});
  auto map = std::make_shared<MultiResMap>();
  for (std::size_t i = 0; i < sim.log.scans.size(); i += 2)
    map->insert_scan(sim.ground_truth[i].second, sim.log.scans[i].laser_offset, scan_to_points(sim.log.scans[i]));
  MapSnapshot s;
  s.sender = "sim";
  s.layers.push_back({"sim", sim.log.scans.size() / 2, Pose2(), 0, map, {}});

  const auto t0 = std::chrono::steady_clock::now();
  const Bytes bytes = encode_dsmap(s);
  const auto t1 = std::chrono::steady_clock::now();
  const MapSnapshot back = decode_dsmap(bytes, "mem");
  const auto t2 = std::chrono::steady_clock::now();
  expect_same_snapshot(s, back);

  std::uint64_t payload = 0;
  for (int i = 0; i < 8; ++i) payload |= std::uint64_t{bytes[15 + static_cast<std::size_t>(i)]} << (8 * i);
  const double cells = static_cast<double>(map->cells_allocated());
  const double per_cell = static_cast<double>(bytes.size()) / cells;
  std::printf("[ dsmap    ] simulated building: %zu cells allocated (%zu tiles on 3 levels), in memory %.1f MB; "
              ".dsmap %zu bytes = %.3f bytes/cell (payload %llu bytes, zstd ratio %.1f); encode %.0f ms, decode %.0f ms\n",
              map->cells_allocated(), map->cells_allocated() / DsGrid::kTileCells,
              static_cast<double>(map->memory_bytes()) / 1e6, bytes.size(), per_cell,
              static_cast<unsigned long long>(payload), static_cast<double>(payload) / static_cast<double>(bytes.size()),
              std::chrono::duration<double, std::milli>(t1 - t0).count(),
              std::chrono::duration<double, std::milli>(t2 - t1).count());
  EXPECT_LT(per_cell, 1.0);  // 4 bytes per cell in memory; the file must be far smaller
}

}  // namespace
}  // namespace dsswarm
