#include "agent/proximity_player.hpp"

#include <gtest/gtest.h>

#include <mutex>

namespace dsswarm::agent {
namespace {

using namespace std::chrono_literals;

TEST(ProximityPlayer, EventsOverBeforeItStartedAreNotRaised) {
  // The run began 10 s ago (a robot restarted in the middle of it); lead 1 s.
  const auto start = std::chrono::system_clock::now() - 10s;
  std::vector<TimedProximity> events;
  for (const double t : {0.0, 5.0, 8.5, 9.5, 10.6})
    events.push_back({t, protocol::Proximity{"a", "b", events.size(), 1.0, 1.0}});
  std::mutex mutex;
  std::vector<std::uint64_t> raised;
  ProximityPlayer player(events, 1.0, 1.0, start, [&](const protocol::Proximity& e) {
    std::lock_guard lock(mutex);
    raised.push_back(e.event);
  });
  player.wait();
  EXPECT_EQ(raised, (std::vector<std::uint64_t>{3, 4}));  // within the lead of now, or still to come
  EXPECT_EQ(player.skipped(), 3u);
}

TEST(ProximityPlayer, RaisesEachEventLeadSecondsBeforeItsTime) {
  std::vector<TimedProximity> events{{0.0, {"a", "b", 0, 1.0, 1.0}}, {0.8, {"a", "b", 1, 1.0, 1.0}}};
  std::vector<double> when;
  const auto t0 = std::chrono::steady_clock::now();
  ProximityPlayer player(events, 2.0, 0.1, std::nullopt, [&](const protocol::Proximity&) {
    when.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  });
  player.wait();
  ASSERT_EQ(when.size(), 2u);
  EXPECT_LT(when[0], 0.1);
  EXPECT_NEAR(when[1], 0.8 / 2.0 - 0.1, 0.05);
  EXPECT_EQ(player.skipped(), 0u);
}

}  // namespace
}  // namespace dsswarm::agent
