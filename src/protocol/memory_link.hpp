#pragma once
// Robots in one process talking through memory, as they would over DDS:
// per-recipient queues, broadcasts to everyone else, and optional loss for
// tests of what survives a bad link.
#include <condition_variable>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "common/rng.hpp"
#include "protocol/link.hpp"

namespace dsswarm::protocol {

class MemoryBus : public std::enable_shared_from_this<MemoryBus> {
 public:
  // Messages are dropped with probability `loss` (deterministic from `seed`).
  explicit MemoryBus(double loss = 0.0, std::uint64_t seed = 1) : loss_(loss), rng_(seed) {}
  // The link of robot `name` (its inbox is created now).
  std::unique_ptr<SwarmLink> join(const std::string& name);
  // A robot that vanished: its messages in flight are lost, new ones go nowhere.
  void leave(const std::string& name);
  std::uint64_t delivered() const;
  std::uint64_t lost() const;

 private:
  class Link;
  struct Inbox {
    std::vector<std::vector<std::uint8_t>> messages;
    std::condition_variable arrived;
    bool woken = false;
  };
  void detach(const std::string& name, const std::shared_ptr<Inbox>& inbox);
  bool deliver(const std::string& from, const std::string& to, std::span<const std::uint8_t> bytes);

  mutable std::mutex mutex_;
  std::map<std::string, std::shared_ptr<Inbox>> inboxes_;
  double loss_;
  Rng rng_;
  std::uint64_t delivered_ = 0, lost_ = 0;
};

}  // namespace dsswarm::protocol
