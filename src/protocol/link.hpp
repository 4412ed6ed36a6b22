#pragma once
// Bytes between robots. Between robot processes this is DDS (net/); in tests
// several runtimes share a MemoryBus. Delivery to one recipient is in order;
// nothing here knows what the bytes mean (wire.hpp does).
#include <chrono>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace dsswarm::protocol {

class SwarmLink {
 public:
  virtual ~SwarmLink() = default;
  // To one robot, or to every robot listening when `recipient` is "".
  // Returns false when the message could not be handed over (the transport
  // is congested or the robot unreachable); the protocol's time-outs cover it.
  virtual bool send(const std::string& recipient, std::span<const std::uint8_t> bytes) = 0;
  // Whether `recipient` is there to take messages: after a refused send,
  // true means its inbox is full (the robot is busy), false that it is gone
  // or not authorized.
  virtual bool reachable(const std::string& recipient) = 0;
  // What has arrived, waiting up to `timeout` for the first message.
  virtual std::vector<std::vector<std::uint8_t>> receive(std::chrono::milliseconds timeout) = 0;
  // Makes a waiting receive() return at once (from any thread).
  virtual void wake() = 0;
};

}  // namespace dsswarm::protocol
