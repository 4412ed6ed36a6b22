#include "runtime/worker_thread.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <ctime>
#include <vector>

#include "sim/loop_world.hpp"
#include "slam/slam.hpp"

namespace dsswarm {
namespace {

TEST(WorkerThread, RunsJobsInOrderOffTheCallingThreadAndWaitSeesThemDone) {
  WorkerThread worker;
  std::vector<int> done;  // written by the worker only, read after wait()
  std::thread::id ran_on;
  for (int i = 0; i < 5; ++i)
    worker.submit([&done, &ran_on, i] {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
      done.push_back(i);
      ran_on = std::this_thread::get_id();
    });
  worker.wait();
  EXPECT_EQ(done, (std::vector<int>{0, 1, 2, 3, 4}));
  EXPECT_NE(ran_on, std::this_thread::get_id());
  EXPECT_GT(worker.waited_seconds(), 0.0);
}

TEST(WorkerThread, WaitingForOneJobDoesNotWaitForTheJobsAfterIt) {
  WorkerThread worker;
  std::atomic<bool> release{false};
  std::atomic<int> done{0};
  const std::uint64_t first = worker.submit([&done] { ++done; });
  const std::uint64_t second = worker.submit([&done] { ++done; });
  const std::uint64_t third = worker.submit([&done, &release] {
    while (!release) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    ++done;
  });
  EXPECT_EQ(second, first + 1);
  EXPECT_EQ(third, first + 2);
  worker.wait_for(second);  // would hang if it waited for the third
  EXPECT_GE(done.load(), 2);
  release = true;
  worker.wait();
  EXPECT_EQ(done.load(), 3);
}

TEST(WorkerThread, CountsTheCpuTimeOfItsJobs) {
  WorkerThread worker;
  std::atomic<double> sink{0.0};
  // The job spins until its thread has used 30 ms of CPU (not of wall time:
  // on a loaded machine 50 ms of wall time may be a few ms of CPU).
  worker.submit([&sink] {
    const auto thread_cpu = [] {
      timespec t{};
      clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
      return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
    };
    const double until = thread_cpu() + 0.03;
    double x = 0.0;
    while (thread_cpu() < until) x += 1e-9;
    sink = x;
  });
  worker.wait();
  EXPECT_GE(worker.cpu_seconds(), 0.03);
  EXPECT_GT(sink.load(), 0.0);
}

TEST(WorkerThread, DestroyingItFinishesWhatWasSubmitted) {
  std::atomic<int> count{0};
  {
    WorkerThread worker;
    for (int i = 0; i < 10; ++i) worker.submit([&count] { ++count; });
  }
  EXPECT_EQ(count.load(), 10);
  // Waiting with nothing submitted returns at once.
  WorkerThread idle;
  idle.wait();
}

}  // namespace
}  // namespace dsswarm

namespace dsswarm {
namespace {

// Loop closing on a thread of its own gives the same map and trajectory as
// on the calling thread: rounds are picked up at the same scans either way.
// With more rounds in flight the corrections come later, yet every round
// starts from the one before it, so the rounds and the end are the same.
TEST(WorkerThread, LoopClosingInTheBackgroundGivesTheSameResultAsInline) {
  LoopWorldConfig world;
  world.laps = 1.15;
  const LoopWorld w = make_loop_world(world);
  LidarConfig lidar;
  lidar.range_max = 8.0;
  RobotConfig robot;
  robot.odom_drift = 0.05;
  const SimulatedRun sim = simulate_run(w.world, w.tour, w.start, robot, lidar, 2);
  SlamConfig one_in_flight = with_loop_closure(), three_in_flight = with_loop_closure();
  one_in_flight.loop_closure.rounds_in_flight = 1;
  three_in_flight.loop_closure.rounds_in_flight = 3;
  Slam inline_slam(one_in_flight);
  WorkerThread worker;
  Slam background_slam(one_in_flight, &worker);
  WorkerThread worker3;
  Slam lagging_slam(three_in_flight, &worker3);
  for (const LaserScan& s : sim.log.scans) {
    const SlamStep a = inline_slam.process(s), b = background_slam.process(s);
    lagging_slam.process(s);
    ASSERT_EQ(a.pose.x, b.pose.x);
    ASSERT_EQ(a.pose.theta, b.pose.theta);
  }
  inline_slam.finish();
  background_slam.finish();
  lagging_slam.finish();
  ASSERT_GT(inline_slam.loop_closer().stats().accepted, 0u);
  EXPECT_EQ(inline_slam.loop_closer().stats().accepted, background_slam.loop_closer().stats().accepted);
  EXPECT_EQ(inline_slam.loop_closer().stats().accepted, lagging_slam.loop_closer().stats().accepted);
  const std::vector<Pose2> a = inline_slam.trajectory(), b = background_slam.trajectory(),
                           c = lagging_slam.trajectory();
  ASSERT_EQ(a.size(), b.size());
  ASSERT_EQ(a.size(), c.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].x, b[i].x) << i;
    ASSERT_EQ(a[i].y, b[i].y) << i;
    ASSERT_EQ(a[i].x, c[i].x) << i;
    ASSERT_EQ(a[i].y, c[i].y) << i;
  }
  EXPECT_GT(worker.cpu_seconds(), 0.0);
}

}  // namespace
}  // namespace dsswarm
