#include "net/security/test/peer_process.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <stdexcept>
#include <thread>

extern char** environ;

namespace dsswarm::sectest {

namespace {

using Clock = std::chrono::steady_clock;

Clock::time_point deadline_after(double seconds) {
  return Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
}

int ms_until(Clock::time_point deadline) {
  const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
  return left > 0 ? static_cast<int>(left) : 0;
}

double cpu_of(const rusage& ru) {
  return static_cast<double>(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) +
         static_cast<double>(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec) * 1e-6;
}

}  // namespace

PeerProcess::PeerProcess(const std::string& program, const std::vector<std::string>& args,
                         const std::filesystem::path& stderr_log) {
  int pipe_fds[2];
  if (::pipe2(pipe_fds, O_CLOEXEC) != 0) throw std::runtime_error("pipe2 failed");
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], STDOUT_FILENO);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, stderr_log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  std::vector<char*> argv{const_cast<char*>(program.c_str())};
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const int rc = posix_spawn(&pid_, program.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(pipe_fds[1]);
  fd_ = pipe_fds[0];
  if (rc != 0) {
    ::close(fd_);
    throw std::runtime_error("cannot start " + program);
  }
}

PeerProcess::~PeerProcess() {
  kill_now();
  if (fd_ >= 0) ::close(fd_);
}

bool PeerProcess::read_some(double seconds) {
  pollfd p{fd_, POLLIN, 0};
  if (::poll(&p, 1, ms_until(deadline_after(seconds))) <= 0) return true;
  char buf[4096];
  const ssize_t n = ::read(fd_, buf, sizeof buf);
  if (n <= 0) return false;
  partial_.append(buf, static_cast<std::size_t>(n));
  for (std::size_t eol; (eol = partial_.find('\n')) != std::string::npos; partial_.erase(0, eol + 1)) {
    lines_.push_back(partial_.substr(0, eol));
  }
  return true;
}

std::optional<std::string> PeerProcess::wait_for(const std::string& prefix, double seconds, std::size_t occurrence) {
  const auto deadline = deadline_after(seconds);
  for (std::size_t checked = 0, found = 0;;) {
    for (; checked < lines_.size(); ++checked)
      if (lines_[checked].rfind(prefix, 0) == 0 && ++found == occurrence) return lines_[checked];
    if (Clock::now() >= deadline) return std::nullopt;
    if (!read_some(static_cast<double>(ms_until(deadline)) / 1000.0)) {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));  // output closed: nothing more will come
      if (checked == lines_.size()) return std::nullopt;
    }
  }
}

void PeerProcess::drain(double seconds) {
  const auto deadline = deadline_after(seconds);
  while (Clock::now() < deadline && read_some(static_cast<double>(ms_until(deadline)) / 1000.0)) {
  }
}

std::vector<std::string> PeerProcess::lines_with(const std::string& prefix) const {
  std::vector<std::string> out;
  for (const auto& l : lines_)
    if (l.rfind(prefix, 0) == 0) out.push_back(l);
  return out;
}

std::optional<int> PeerProcess::exit_code(double seconds) {
  const auto deadline = deadline_after(seconds);
  while (!status_) {
    int st = 0;
    rusage ru{};
    if (::wait4(pid_, &st, WNOHANG, &ru) == pid_) {
      status_ = WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
      cpu_seconds_ = cpu_of(ru);
      break;
    }
    if (Clock::now() >= deadline) return std::nullopt;
    drain(0.02);
  }
  drain(0.0);
  return status_;
}

void PeerProcess::kill_now() {
  if (status_ || pid_ <= 0) return;
  ::kill(pid_, SIGKILL);
  int st = 0;
  rusage ru{};
  ::wait4(pid_, &st, 0, &ru);
  status_ = 128 + SIGKILL;
  cpu_seconds_ = cpu_of(ru);
}

int PeerProcess::stop(double seconds) {
  if (!status_) ::kill(pid_, SIGTERM);
  if (!exit_code(seconds)) kill_now();
  return *status_;
}

}  // namespace dsswarm::sectest
