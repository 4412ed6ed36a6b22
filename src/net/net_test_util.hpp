#pragma once
// For DDS tests: a domain and a ROS namespace of the running test's own, so
// tests run in parallel (ctest -j, other checkouts on this machine) never see
// each other's samples, on loopback with unicast discovery.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <functional>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "net/dds.hpp"

namespace dsswarm::net::test {

inline std::string test_id() {
  const auto* info = testing::UnitTest::GetInstance()->current_test_info();
  return std::string(info->test_suite_name()) + "." + info->name() + "." + std::to_string(getpid());
}

// Domains 100..229: away from 0 (ROS 2's default) and the low ids people use.
inline constexpr std::uint32_t kFirstTestDomain = 100, kTestDomains = 130;

// Takes the lock file of `domain` in `dir`: the descriptor holding it, or -1
// when another claim holds it (a second open of the file conflicts even in
// this process) or the file cannot be opened.
inline int lock_domain(const std::filesystem::path& dir, std::uint32_t domain) {
  const std::string lock = (dir / (std::to_string(domain) + ".lock")).string();
  const int fd = ::open(lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
  if (fd < 0 || ::flock(fd, LOCK_EX | LOCK_NB) == 0) return fd;
  ::close(fd);
  return -1;
}

// The running test's k-th domain, claimed for it alone on this machine: a
// lock file per domain (flock, released when the process ends or the next
// test of the process claims), so two tests running side by side never share
// a domain. Absolute topics such as /tf_static are not separated by the
// test's namespace. The search starts at a hash of the test, so most claims
// succeed at once.
inline std::uint32_t test_domain(int k = 0) {
  struct Claims {
    std::string test;
    std::map<int, std::uint32_t> domains;  // k -> domain
    std::vector<int> fds;
    void release() {
      for (int fd : fds) ::close(fd);  // closing drops the flock
      fds.clear();
      domains.clear();
    }
  };
  static Claims claims;
  const std::string id = test_id();
  if (claims.test != id) claims.release(), claims.test = id;
  if (const auto it = claims.domains.find(k); it != claims.domains.end()) return it->second;

  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "dsswarm-test-domains";
  std::error_code ignored;
  std::filesystem::create_directories(dir, ignored);
  const std::uint32_t start = static_cast<std::uint32_t>(std::hash<std::string>{}(id + "#" + std::to_string(k)) % kTestDomains);
  for (std::uint32_t i = 0; i < kTestDomains; ++i) {
    const std::uint32_t domain = kFirstTestDomain + (start + i) % kTestDomains;
    if (const int fd = lock_domain(dir, domain); fd >= 0) {
      claims.fds.push_back(fd);
      return claims.domains[k] = domain;
    }
  }
  const std::uint32_t fallback = kFirstTestDomain + start;  // no lock possible: the hash alone, as before
  std::cerr << "test_domain: could not claim a domain in " << dir << ", using " << fallback << " unclaimed\n";
  return claims.domains[k] = fallback;
}

inline std::string test_namespace() { return "/test_" + std::to_string(getpid()); }

inline ParticipantConfig loopback_config() {
  ParticipantConfig config;
  config.domain_id = test_domain();
  config.interface = "lo";
  return config;
}

// Float readings as their bit patterns: NaN compares equal to itself.
inline std::vector<std::uint32_t> bits(const std::vector<float>& v) {
  std::vector<std::uint32_t> out(v.size());
  std::memcpy(out.data(), v.data(), v.size() * sizeof(float));
  return out;
}

}  // namespace dsswarm::net::test
