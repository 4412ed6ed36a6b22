#include "agent/triggers.hpp"

#include <gtest/gtest.h>

namespace dsswarm::agent {
namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

TEST(TriggerBook, FiresAfterItsScanOrAtOnceIfThatScanHasPassed) {
  TriggerBook book(5s);
  const auto t0 = Clock::now();
  EXPECT_TRUE(book.arm({"b", 1, 10.2, t0}).empty());
  EXPECT_TRUE(book.armed("b", 1));
  EXPECT_TRUE(book.on_scan(10.1).empty());
  const auto due = book.on_scan(10.2 + 1e-9);  // the stamp as it crossed ROS's sec + nanosec
  ASSERT_EQ(due.size(), 1u);
  EXPECT_EQ(due[0].peer, "b");
  EXPECT_FALSE(due[0].late);
  EXPECT_FALSE(book.armed("b", 1));
  // The event arrived after its scan: it fires at once, marked late.
  const auto late = book.arm({"c", 2, 10.1, t0});
  ASSERT_EQ(late.size(), 1u);
  EXPECT_TRUE(late[0].late);
}

TEST(TriggerBook, AScanThatNeverComesFiresAfterThePatience) {
  TriggerBook book(2s);
  const auto t0 = Clock::now();
  book.arm({"b", 1, 99.0, t0});
  EXPECT_TRUE(book.overdue(t0 + 1s).empty());
  const auto due = book.overdue(t0 + 3s);
  ASSERT_EQ(due.size(), 1u);
  EXPECT_TRUE(due[0].late);
  EXPECT_EQ(book.size(), 0u);
}

}  // namespace
}  // namespace dsswarm::agent
