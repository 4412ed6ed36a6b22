#pragma once
// Child processes started and stopped together (`dsswarm launch`, and the
// multi-process tests): each with its output in a log file, all stopped
// (SIGTERM, then SIGKILL after a grace time) when the group goes.
#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace dsswarm {

class ProcessGroup {
 public:
  ProcessGroup() = default;
  ~ProcessGroup();  // stops whatever still runs
  ProcessGroup(const ProcessGroup&) = delete;
  ProcessGroup& operator=(const ProcessGroup&) = delete;

  // Starts `argv` (argv[0] a path) with stdout and stderr appended to `log`
  // and `env` ("KEY=value") added to this process's environment. Returns an
  // index for the calls below. Throws std::runtime_error if it cannot start.
  std::size_t start(const std::vector<std::string>& argv, const std::filesystem::path& log,
                    const std::vector<std::string>& env = {});

  // Exit status once the process has ended (128 + signal when killed), else nullopt.
  std::optional<int> poll(std::size_t index);
  // Waits up to `timeout` for it to end.
  std::optional<int> wait(std::size_t index, std::chrono::milliseconds timeout);
  void signal(std::size_t index, int sig);
  // SIGTERM, then SIGKILL if it has not ended within `grace`. Returns its status.
  int stop(std::size_t index, std::chrono::milliseconds grace = std::chrono::seconds(10));
  void stop_all(std::chrono::milliseconds grace = std::chrono::seconds(10));
  pid_t pid(std::size_t index) const { return children_.at(index).pid; }
  std::size_t size() const { return children_.size(); }

 private:
  struct Child {
    pid_t pid = -1;
    std::optional<int> status;
  };
  std::vector<Child> children_;
};

}  // namespace dsswarm
