#pragma once
// SIGINT / SIGTERM ask a long-running command (agent, replay, proximity,
// launch) to stop cleanly: it flushes its outputs and exits 0. The previous
// handlers come back when the guard goes.
#include <atomic>
#include <csignal>

namespace dsswarm {

class StopOnSignal {
 public:
  StopOnSignal() {
    requested() = false;
    struct sigaction action {};
    action.sa_handler = [](int) { requested() = true; };
    sigemptyset(&action.sa_mask);
    sigaction(SIGINT, &action, &old_int_);
    sigaction(SIGTERM, &action, &old_term_);
  }
  ~StopOnSignal() {
    sigaction(SIGINT, &old_int_, nullptr);
    sigaction(SIGTERM, &old_term_, nullptr);
  }
  StopOnSignal(const StopOnSignal&) = delete;
  StopOnSignal& operator=(const StopOnSignal&) = delete;

  // Set once a signal arrived (lock-free, so a handler may set it).
  static std::atomic<bool>& requested() {
    static std::atomic<bool> flag{false};
    return flag;
  }

 private:
  struct sigaction old_int_ {};
  struct sigaction old_term_ {};
};

}  // namespace dsswarm
