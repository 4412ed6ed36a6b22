#include "protocol/followers.hpp"

#include <gtest/gtest.h>

namespace dsswarm::protocol {
namespace {

TEST(Followers, OnlyPeersThatMergedAreToldAndOnlyOfANewerRevision) {
  Followers f(5.0, 8);
  EXPECT_TRUE(f.due(3, 0.0, false).empty());  // nobody merged yet
  f.add("robot2", {7, 40, Pose2{1.0, 2.0, 0.1}});
  EXPECT_TRUE(f.due(0, 0.0, true).empty());   // nothing ever moved
  EXPECT_EQ(f.due(3, 0.0, false), std::vector<std::string>{"robot2"});
  f.told("robot2", 3, 0.0);
  EXPECT_TRUE(f.due(3, 100.0, false).empty());  // nothing moved since
  EXPECT_TRUE(f.due(4, 1.0, false).empty());    // moved, but told moments ago
  EXPECT_EQ(f.due(4, 1.0, true), std::vector<std::string>{"robot2"});  // the run's end
  EXPECT_EQ(f.due(4, 5.0, false), std::vector<std::string>{"robot2"});
  ASSERT_EQ(f.ties("robot2").size(), 1u);
  EXPECT_EQ(f.ties("robot2")[0].encounter, 7u);
  EXPECT_TRUE(f.ties("robot3").empty());
}

TEST(Followers, APeerThatRestartedIsToldAgainAtOnce) {
  Followers f(5.0, 8);
  f.add("robot2", {7, 40, Pose2{}});
  f.told("robot2", 3, 0.0);
  EXPECT_TRUE(f.due(3, 100.0, false).empty());
  f.untold("robot2");
  EXPECT_EQ(f.due(3, 0.5, false), std::vector<std::string>{"robot2"});  // the same revision, moments later
  f.untold("robot3");  // never a follower: nothing to tell it
  EXPECT_EQ(f.due(3, 0.5, false), std::vector<std::string>{"robot2"});
}

TEST(Followers, KeepsTheLatestEncountersPerPeer) {
  Followers f(1.0, 2);
  for (std::uint64_t e = 1; e <= 5; ++e) f.add("robot2", {e, e, Pose2{}});
  ASSERT_EQ(f.ties("robot2").size(), 2u);
  EXPECT_EQ(f.ties("robot2")[0].encounter, 4u);
  EXPECT_EQ(f.ties("robot2")[1].encounter, 5u);
}

TEST(Followers, AMovedOvertakenByALaterOneIsIgnored) {
  Followers f(1.0, 8);
  EXPECT_TRUE(f.newer("robot2", 10, 4));
  EXPECT_FALSE(f.newer("robot2", 10, 4));  // the same again
  EXPECT_FALSE(f.newer("robot2", 10, 3));  // older
  EXPECT_TRUE(f.newer("robot2", 10, 5));
  EXPECT_TRUE(f.newer("robot2", 11, 1));   // a new run of it starts over
  EXPECT_FALSE(f.newer("robot2", 10, 9));  // the earlier run's
  EXPECT_TRUE(f.newer("robot3", 10, 1));   // per sender
}

}  // namespace
}  // namespace dsswarm::protocol
