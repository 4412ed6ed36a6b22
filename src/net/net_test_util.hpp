#pragma once
// For DDS tests: a domain and a ROS namespace of the running test's own, so
// tests run in parallel (ctest -j, other checkouts on this machine) never see
// each other's samples, on loopback with unicast discovery.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "net/dds.hpp"

namespace dsswarm::net::test {

inline std::string test_id() {
  const auto* info = testing::UnitTest::GetInstance()->current_test_info();
  return std::string(info->test_suite_name()) + "." + info->name() + "." + std::to_string(getpid());
}

// Domains 100..229: away from 0 (ROS 2's default) and the low ids people use.
inline std::uint32_t test_domain() {
  return 100 + static_cast<std::uint32_t>(std::hash<std::string>{}(test_id()) % 130);
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
