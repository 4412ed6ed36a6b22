#pragma once
// An Executor (slam/executor.hpp) with a thread of its own: jobs run one
// after the other, in the order submitted, while the submitting thread goes
// on. The thread plumbing the core leaves out lives here.
#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>

#include "slam/executor.hpp"

namespace dsswarm {

class WorkerThread final : public Executor {
 public:
  // After a job, at most once every `trim_interval`, memory the allocator
  // holds free is handed back to the system (glibc): a long run then does not
  // keep what its largest rounds once needed. Not after every job: a trim
  // unmaps pages the next job faults in again, and its TLB flush interrupts
  // the other cores, the scan path's among them (docs/performance.md).
  explicit WorkerThread(std::chrono::milliseconds trim_interval = std::chrono::seconds(10));
  // Finishes the jobs already submitted, then stops the thread.
  ~WorkerThread() override;
  WorkerThread(const WorkerThread&) = delete;
  WorkerThread& operator=(const WorkerThread&) = delete;

  std::uint64_t submit(std::function<void()> job) override;
  void wait_for(std::uint64_t ticket) override;
  void wait() override;

  // CPU time the thread has spent in jobs so far, seconds.
  double cpu_seconds() const;
  // Wall time submitters spent in wait() for jobs still running, seconds.
  double waited_seconds() const;

 private:
  void run();
  void wait_until(std::unique_lock<std::mutex>& lock, std::uint64_t ticket);

  mutable std::mutex mutex_;
  std::condition_variable work_or_stop_;
  std::condition_variable idle_;
  std::deque<std::function<void()>> jobs_;
  std::uint64_t submitted_ = 0;
  std::uint64_t finished_ = 0;
  bool stop_ = false;
  double cpu_seconds_ = 0.0;
  double waited_seconds_ = 0.0;
  std::chrono::milliseconds trim_interval_;
  std::thread thread_;  // last: starts once everything above exists
};

}  // namespace dsswarm
