#pragma once
// A security_test_peer child process for the DDS Security tests: started
// with posix_spawn, its stdout read line by line with deadlines, its stderr
// kept in a log file; killed (SIGKILL) and reaped when the object goes away,
// so a failing test never leaves processes behind.
#include <sys/types.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace dsswarm::sectest {

class PeerProcess {
 public:
  // Runs `program args...`; stderr goes to `stderr_log`.
  PeerProcess(const std::string& program, const std::vector<std::string>& args, const std::filesystem::path& stderr_log);
  ~PeerProcess();
  PeerProcess(const PeerProcess&) = delete;
  PeerProcess& operator=(const PeerProcess&) = delete;

  // Reads output until the `occurrence`-th line starting with `prefix` has
  // arrived (returned) or `seconds` pass (nullopt). Lines already read count.
  std::optional<std::string> wait_for(const std::string& prefix, double seconds, std::size_t occurrence = 1);
  // Reads output for `seconds`.
  void drain(double seconds);
  // Lines read so far that start with `prefix`.
  std::vector<std::string> lines_with(const std::string& prefix) const;

  void kill_now();                     // SIGKILL, reaped
  int stop(double seconds);            // SIGTERM; SIGKILL after `seconds`; the exit status
  std::optional<int> exit_code(double seconds);  // waits for it to exit on its own
  const std::vector<std::string>& lines() const { return lines_; }
  // User + system CPU seconds of the process, once it has been reaped.
  double cpu_seconds() const { return cpu_seconds_; }

 private:
  bool read_some(double seconds);  // false at end of output

  pid_t pid_ = -1;
  int fd_ = -1;
  std::string partial_;
  std::vector<std::string> lines_;
  std::optional<int> status_;
  double cpu_seconds_ = 0;
};

}  // namespace dsswarm::sectest
