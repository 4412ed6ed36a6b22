#pragma once
// The swarm's own topic type (swarm_msgs.idl): bytes in the swarm protocol's
// encoding. Not a ROS type, so no ROS type hash.
#include <cstdint>
#include <span>

#include "net/dds.hpp"
#include "swarm_msgs.h"

namespace dsswarm::net {

using SwarmPacket = dsswarm_msg_Packet;

template <>
struct TopicType<SwarmPacket> {
  static const dds_topic_descriptor_t& descriptor() { return dsswarm_msg_Packet_desc; }
  static constexpr std::string_view ros_type_hash = "";
};

// A packet pointing at `payload` (no copy): valid while `payload` lives.
inline SwarmPacket packet_view(std::span<const std::uint8_t> payload) {
  SwarmPacket packet{};
  packet.payload._buffer = const_cast<std::uint8_t*>(payload.data());
  packet.payload._length = static_cast<std::uint32_t>(payload.size());
  packet.payload._maximum = packet.payload._length;
  packet.payload._release = false;
  return packet;
}

// The bytes of a received packet (valid while the sample is).
inline std::span<const std::uint8_t> packet_payload(const SwarmPacket& packet) {
  return {packet.payload._buffer, packet.payload._length};
}

}  // namespace dsswarm::net
