#pragma once
// Everything a robot receives passes here first: decoded and validated
// (wire.hpp), then checked to be for this robot, not its own echo, and not
// a replay. What fails is counted by reason and never reaches the robot.
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <utility>

#include "protocol/wire.hpp"

namespace dsswarm::protocol {

class MessageGate {
 public:
  // At most `max_senders` distinct senders are tracked (a flood of invented
  // names cannot grow the gate's memory); messages from more are refused.
  explicit MessageGate(std::string self, WireLimits limits = {}, std::size_t max_senders = 1024)
      : self_(std::move(self)), limits_(limits), max_senders_(max_senders) {}

  struct Verdict {
    std::optional<Message> message;  // set when accepted
    std::string rejected;            // why not ("" when accepted or ignored)
    bool peer_restarted = false;     // the sender has a new incarnation
  };
  // Own messages (a transport may echo them) are ignored, not counted.
  Verdict admit(std::span<const std::uint8_t> bytes);

  std::uint64_t accepted() const { return accepted_; }
  std::uint64_t rejected() const { return rejected_total_; }
  const std::map<std::string, std::uint64_t>& rejected_by_reason() const { return rejected_by_reason_; }

 private:
  struct Stream {
    std::uint64_t incarnation = 0;
    std::uint64_t sequence = 0;
  };
  Verdict reject(const std::string& category, std::string detail);

  std::string self_;
  WireLimits limits_;
  std::size_t max_senders_;
  // Per (sender, directed to us or broadcast): each travels in order on its
  // own topic, so each has its own sequence.
  std::map<std::pair<std::string, bool>, Stream> streams_;
  std::map<std::string, std::uint64_t> incarnations_;  // newest seen per sender
  std::uint64_t accepted_ = 0;
  std::uint64_t rejected_total_ = 0;
  std::map<std::string, std::uint64_t> rejected_by_reason_;
};

// Numbers each outgoing message: one sequence per recipient ("" for
// broadcasts), matching the gate's streams.
class MessageStamper {
 public:
  MessageStamper(std::string self, std::uint64_t incarnation) : self_(std::move(self)), incarnation_(incarnation) {}
  Message stamp(std::string recipient, Body body);
  const std::string& self() const { return self_; }

 private:
  std::string self_;
  std::uint64_t incarnation_;
  std::map<std::string, std::uint64_t> next_;
};

}  // namespace dsswarm::protocol
