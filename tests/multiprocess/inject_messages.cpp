// Test tool for scripts/fault_table.sh: sends rounds of bad swarm messages
// (multiprocess.hpp's bad_messages) into a robot's inbox on loopback, as a
// plain unsecured DDS participant, and prints what the robot should count.
//   multiprocess_inject DOMAIN SWARM ROBOT ROUNDS INTERVAL_S
#include <fmt/format.h>

#include <cstdlib>
#include <iostream>
#include <map>
#include <thread>

#include "multiprocess.hpp"

int main(int argc, char** argv) {
  using namespace dsswarm;
  if (argc != 6) {
    std::cerr << "usage: multiprocess_inject DOMAIN SWARM ROBOT ROUNDS INTERVAL_S\n";
    return 2;
  }
  const int domain = std::atoi(argv[1]), rounds = std::atoi(argv[4]);
  const std::string robot = argv[3];
  const auto interval = std::chrono::duration<double>(std::atof(argv[5]));
  mp::SwarmTap tap(domain, net::swarm_partition(argv[2]), "mallory");
  if (!mp::wait_for_heartbeat(tap, robot, std::chrono::seconds(30))) {
    std::cerr << "error: no heartbeat from " << robot << " within 30 s\n";
    return 1;
  }
  protocol::MessageStamper mallory("mallory", 7);
  std::map<std::string, int> expected;
  for (int r = 0; r < rounds; ++r) {
    for (const auto& [reason, bytes] : mp::bad_messages(mallory, robot)) {
      if (!tap.link.send(robot, bytes)) {
        std::cerr << "error: could not send to " << robot << "\n";
        return 1;
      }
      if (!reason.empty()) ++expected[reason];
    }
    std::this_thread::sleep_for(interval);
  }
  std::string summary;
  for (const auto& [reason, n] : expected) summary += fmt::format("{}{}: {}", summary.empty() ? "" : ", ", reason, n);
  std::cout << summary << "\n";
  return 0;
}
