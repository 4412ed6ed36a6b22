#include "runtime/worker_thread.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <vector>

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

TEST(WorkerThread, CountsTheCpuTimeOfItsJobs) {
  WorkerThread worker;
  std::atomic<double> sink{0.0};
  worker.submit([&sink] {
    double x = 0.0;
    const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(50);
    while (std::chrono::steady_clock::now() < until) x += 1e-9;
    sink = x;
  });
  worker.wait();
  EXPECT_GT(worker.cpu_seconds(), 0.02);
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
