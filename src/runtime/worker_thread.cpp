#include "runtime/worker_thread.hpp"

#include <time.h>

#include <chrono>

#include "common/process_usage.hpp"

namespace dsswarm {
namespace {
double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}
}  // namespace

WorkerThread::WorkerThread(std::chrono::milliseconds trim_interval)
    : trim_interval_(trim_interval), thread_([this] { run(); }) {}

WorkerThread::~WorkerThread() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  work_or_stop_.notify_one();
  thread_.join();
}

std::uint64_t WorkerThread::submit(std::function<void()> job) {
  std::uint64_t ticket = 0;
  {
    std::lock_guard lock(mutex_);
    jobs_.push_back(std::move(job));
    ticket = ++submitted_;
  }
  work_or_stop_.notify_one();
  return ticket;
}

void WorkerThread::wait_until(std::unique_lock<std::mutex>& lock, std::uint64_t ticket) {
  const auto t0 = std::chrono::steady_clock::now();
  idle_.wait(lock, [&] { return finished_ >= ticket; });
  waited_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void WorkerThread::wait_for(std::uint64_t ticket) {
  std::unique_lock lock(mutex_);
  wait_until(lock, ticket);
}

void WorkerThread::wait() {
  std::unique_lock lock(mutex_);
  wait_until(lock, submitted_);
}

double WorkerThread::cpu_seconds() const {
  std::lock_guard lock(mutex_);
  return cpu_seconds_;
}

double WorkerThread::waited_seconds() const {
  std::lock_guard lock(mutex_);
  return waited_seconds_;
}

void WorkerThread::run() {
  auto next_trim = std::chrono::steady_clock::now() + trim_interval_;
  std::unique_lock lock(mutex_);
  for (;;) {
    work_or_stop_.wait(lock, [this] { return stop_ || !jobs_.empty(); });
    if (jobs_.empty()) return;  // stopping, nothing left
    std::function<void()> job = std::move(jobs_.front());
    jobs_.pop_front();
    lock.unlock();
    const double t0 = thread_cpu_seconds();
    job();
    // A job's scratch memory (thawed submaps, bounds, the solver's matrices)
    // is freed in scattered pieces that glibc keeps resident for the next job.
    if (std::chrono::steady_clock::now() >= next_trim) {
      release_free_heap();
      next_trim = std::chrono::steady_clock::now() + trim_interval_;
    }
    const double spent = thread_cpu_seconds() - t0;
    lock.lock();
    cpu_seconds_ += spent;
    ++finished_;
    idle_.notify_all();
  }
}

}  // namespace dsswarm
