#pragma once
// Where background work runs. The core hands over whole jobs — pure
// functions of data it no longer touches until the job is done — and asks
// later to wait for them; it owns no threads itself. The default runs each
// job at once, on the caller's thread; runtime/worker_thread.hpp runs them
// on a thread of their own. Results are picked up at the same points either
// way, so both give the same output.
#include <cstdint>
#include <functional>

namespace dsswarm {

class Executor {
 public:
  virtual ~Executor() = default;
  // Runs `job` (now, or on another thread). Jobs run one after the other in
  // the order submitted; returns the job's ticket (1 for the first, then 2, …).
  virtual std::uint64_t submit(std::function<void()> job) = 0;
  // Returns once the job with `ticket`, and so every job before it, has finished.
  virtual void wait_for(std::uint64_t ticket) = 0;
  // Returns once every job submitted so far has finished.
  virtual void wait() = 0;
};

class InlineExecutor final : public Executor {
 public:
  std::uint64_t submit(std::function<void()> job) override {
    job();
    return ++submitted_;
  }
  void wait_for(std::uint64_t) override {}
  void wait() override {}

 private:
  std::uint64_t submitted_ = 0;
};

}  // namespace dsswarm
