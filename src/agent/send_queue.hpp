#pragma once
// Messages to a peer whose inbox is full: the peer is there but busy (its
// swarm thread placing a scan while a snapshot streams in), so a refused
// message waits, in order with the ones after it, and goes out on the swarm
// thread's next rounds instead of ending the exchange. A peer that cannot be
// reached, or whose inbox takes nothing for `patience` seconds, is given up.
#include <cstddef>
#include <cstdint>
#include <deque>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "protocol/link.hpp"

namespace dsswarm::agent {

class SendQueue {
 public:
  explicit SendQueue(double patience) : patience_(patience) {}

  // Sends now, or queues behind what already waits for `recipient`.
  void send(protocol::SwarmLink& link, const std::string& recipient, std::vector<std::uint8_t> bytes, double now);
  // Sends what waits, each peer's in order, until its inbox refuses again.
  void retry(protocol::SwarmLink& link, double now);
  // Drops what waits for `recipient` (it restarted, or went silent: the
  // messages were for encounters that ended).
  void forget(const std::string& recipient) { waiting_.erase(recipient); }
  // The peers given up since the last call, each with why.
  std::vector<std::pair<std::string, std::string>> take_given_up();
  std::size_t waiting() const;  // messages, all peers
  std::uint64_t deferred() const { return deferred_; }  // messages that had to wait, ever

 private:
  struct Waiting {
    std::deque<std::vector<std::uint8_t>> messages;
    double since = 0.0;  // last progress
  };
  void give_up(const std::string& recipient, std::string why);

  double patience_;
  std::map<std::string, Waiting> waiting_;
  std::map<std::string, std::string> given_up_;  // until taken: later messages to them are dropped
  std::uint64_t deferred_ = 0;
};

}  // namespace dsswarm::agent
