#include "apps/process_group.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <thread>

extern char** environ;

namespace dsswarm {

ProcessGroup::~ProcessGroup() { stop_all(std::chrono::seconds(5)); }

std::size_t ProcessGroup::start(const std::vector<std::string>& argv, const std::filesystem::path& log,
                                const std::vector<std::string>& env) {
  if (argv.empty()) throw std::invalid_argument("ProcessGroup::start: no program");
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  std::vector<std::string> environment;
  for (char** e = environ; *e; ++e) environment.emplace_back(*e);
  environment.insert(environment.end(), env.begin(), env.end());
  std::vector<char*> envp;
  for (const std::string& e : environment) envp.push_back(const_cast<char*>(e.c_str()));
  envp.push_back(nullptr);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, argv[0].c_str(), &actions, nullptr, args.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) throw std::runtime_error("cannot start " + argv[0] + ": " + std::strerror(rc));
  children_.push_back({pid, std::nullopt});
  return children_.size() - 1;
}

std::optional<int> ProcessGroup::poll(std::size_t index) {
  Child& c = children_.at(index);
  if (c.status) return c.status;
  int status = 0;
  const pid_t r = waitpid(c.pid, &status, WNOHANG);
  if (r == c.pid) c.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  else if (r < 0 && errno == ECHILD) c.status = -1;
  return c.status;
}

std::optional<int> ProcessGroup::wait(std::size_t index, std::chrono::milliseconds timeout) {
  const auto until = std::chrono::steady_clock::now() + timeout;
  for (;;) {
    if (auto s = poll(index)) return s;
    if (std::chrono::steady_clock::now() >= until) return std::nullopt;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

void ProcessGroup::signal(std::size_t index, int sig) {
  if (!poll(index)) ::kill(children_.at(index).pid, sig);
}

int ProcessGroup::stop(std::size_t index, std::chrono::milliseconds grace) {
  signal(index, SIGTERM);
  if (auto s = wait(index, grace)) return *s;
  signal(index, SIGKILL);
  return wait(index, std::chrono::seconds(5)).value_or(-1);
}

void ProcessGroup::stop_all(std::chrono::milliseconds grace) {
  for (std::size_t i = 0; i < children_.size(); ++i) signal(i, SIGTERM);
  const auto until = std::chrono::steady_clock::now() + grace;
  for (std::size_t i = 0; i < children_.size(); ++i) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(until - std::chrono::steady_clock::now());
    if (!wait(i, std::max(left, std::chrono::milliseconds(0)))) {
      signal(i, SIGKILL);
      wait(i, std::chrono::seconds(5));
    }
  }
}

}  // namespace dsswarm
