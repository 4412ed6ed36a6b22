#pragma once
// `dsswarm proximity SCENARIO.yaml` (or `--sim SEED`): publishes the
// encounter events of a scenario or of the simulated swarm on time, each as
// a Proximity message to the inboxes of both robots, then exits. Each event
// names, per robot, the stamp of the scan after which it joins
// (agent::proximity_schedule), so robot processes fed by `replay --scenario`
// act after exactly the scan the in-process swarm would. An event goes out
// --lead seconds of wall time before its time (session time / rate): what it
// must beat is the delivery to the robots, which takes wall time at any rate;
// and the agents' trigger patience (10 s) counts from its arrival, so the
// lead stays well below that. The tool's identity in the swarm is
// "proximity": with --keys it needs that certificate (`dsswarm keys add DIR
// proximity`; `dsswarm launch` makes it).
#include <CLI/CLI.hpp>

#include <atomic>
#include <chrono>
#include <set>
#include <string>
#include <vector>

#include "protocol/gate.hpp"
#include "protocol/link.hpp"

namespace dsswarm {

void add_proximity_command(CLI::App& app);

// Sends `event` to both robots it names (one message to each inbox). A robot
// whose inbox is not (yet) discovered is tried again until `wait` has passed
// or `stop` is set, except those `given_up` (one attempt). Returns the robots
// it could not reach.
std::vector<std::string> send_proximity(protocol::SwarmLink& link, protocol::MessageStamper& stamper,
                                        const protocol::Proximity& event, std::chrono::milliseconds wait,
                                        const std::atomic<bool>& stop, const std::set<std::string>& given_up = {});

// A new sender's incarnation: now, in ns since the epoch (as agents take theirs).
std::uint64_t incarnation_now();

}  // namespace dsswarm
