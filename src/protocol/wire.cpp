#include "protocol/wire.hpp"

#include <fmt/format.h>
#include <zlib.h>

#include <set>
#include <string_view>

#include "common/byte_io.hpp"
#include "protocol/body_reader.hpp"

namespace dsswarm::protocol {
namespace {

constexpr std::string_view kMagic = "DSWM";
// magic, version, kind, two empty names, incarnation, sequence, body size, CRC
constexpr std::size_t kMinMessageBytes = 4 + 2 + 1 + 4 + 4 + 8 + 8 + 4 + 4;

std::uint32_t crc_of(std::span<const std::uint8_t> bytes) {
  return static_cast<std::uint32_t>(crc32_z(0, bytes.data(), bytes.size()));
}

// ---- encoding -------------------------------------------------------------

void put(ByteWriter& w, const Pose2& p) {
  w.f64(p.x);
  w.f64(p.y);
  w.f64(p.theta);
}

void put(ByteWriter& w, const std::vector<ScanPoint>& points) {
  w.u32(static_cast<std::uint32_t>(points.size()));
  for (const ScanPoint& p : points) {
    w.f32(p.x);
    w.f32(p.y);
    w.f32(p.weight);
  }
}

void put(ByteWriter& w, const PoseHypothesis& h) {
  put(w, h.pose);
  w.f64(h.score);
  w.f64(h.surroundings_score);
  w.f64(h.inlier_ratio);
  w.f64(h.known_fraction);
  w.f64(h.same_side_ratio);
}

void put_body(ByteWriter& w, const Heartbeat& m) {
  const AgentStatus& s = m.status;
  w.f64(s.uptime);
  w.u64(s.scans_received);
  w.u64(s.scans_processed);
  w.u64(s.scans_skipped);
  w.f64(s.scans_per_second);
  w.u32(s.peers_known);
  w.u32(s.encounters);
  w.u32(s.encounters_accepted);
  w.f64(s.last_merge_age);
  w.u64(s.map_version);
  w.u64(s.messages_rejected);
}

void put_body(ByteWriter& w, const Proximity& m) {
  w.str(m.a);
  w.str(m.b);
  w.u64(m.event);
  w.f64(m.a_stamp);
  w.f64(m.b_stamp);
}

void put_body(ByteWriter& w, const Offer& m) {
  w.u64(m.encounter);
  w.f64(m.stamp);
  put(w, m.pose);
  put(w, m.points);
  put(w, m.surroundings);
  put(w, m.wide_surroundings);
  w.u32(static_cast<std::uint32_t>(m.inventory.size()));
  for (const LayerVersion& l : m.inventory) {
    w.str(l.origin);
    w.u64(l.version);
    w.i32(l.hops);
  }
}

void put_body(ByteWriter& w, const Decline& m) {
  w.u64(m.encounter);
  w.str(m.reason);
}

void put_body(ByteWriter& w, const Placement& m) {
  w.u64(m.encounter);
  const PeerPlacement& p = m.placement;
  w.u8(p.valid ? 1 : 0);
  put(w, p.located.best);
  w.u8(p.located.runner_up ? 1 : 0);
  if (p.located.runner_up) put(w, *p.located.runner_up);
  w.i32(p.located.evaluations);
  w.u8(p.wide ? 1 : 0);
  if (p.wide) put(w, *p.wide);
  w.u8(m.known_transform ? 1 : 0);
  if (m.known_transform) put(w, *m.known_transform);
  w.u32(static_cast<std::uint32_t>(m.pending.size()));
  for (const Pose2& c : m.pending) put(w, c);
  w.f64(m.compute_ms);
}

void put_body(ByteWriter& w, const Chunk& m) {
  w.u64(m.encounter);
  w.u32(m.index);
  w.u32(m.count);
  w.u64(m.total_bytes);
  w.u32(m.total_crc);
  w.u32(static_cast<std::uint32_t>(m.data.size()));
  w.bytes().insert(w.bytes().end(), m.data.begin(), m.data.end());
}

void put_body(ByteWriter& w, const Moved& m) {
  w.u64(m.moves.revision);
  w.u32(static_cast<std::uint32_t>(m.moves.pieces.size()));
  for (const PiecePose& p : m.moves.pieces) {
    w.i32(p.id);
    put(w, p.pose);
  }
  w.u32(static_cast<std::uint32_t>(m.moves.ties.size()));
  for (const TieMove& t : m.moves.ties) {
    w.u64(t.encounter);
    put(w, t.then);
    put(w, t.now);
  }
  w.u32(static_cast<std::uint32_t>(m.moves.closures.size()));
  for (const PeerClosure& c : m.moves.closures) {
    w.i32(c.submap);
    put(w, c.in_cells);
    put(w, c.node);
  }
}

// ---- decoding -------------------------------------------------------------

using wire_detail::BodyReader;

Body read_heartbeat(BodyReader& b) {
  Heartbeat m;
  AgentStatus& s = m.status;
  s.uptime = b.in_range("uptime", 0.0, 1e12);
  s.scans_received = b.raw().u64("scans received");
  s.scans_processed = b.raw().u64("scans processed");
  s.scans_skipped = b.raw().u64("scans skipped");
  s.scans_per_second = b.in_range("scans per second", 0.0, 1e9);
  s.peers_known = b.raw().u32("peers known");
  s.encounters = b.raw().u32("encounters");
  s.encounters_accepted = b.raw().u32("encounters accepted");
  s.last_merge_age = b.in_range("last merge age", -1.0, 1e12);
  s.map_version = b.raw().u64("map version");
  s.messages_rejected = b.raw().u64("messages rejected");
  return m;
}

Body read_proximity(BodyReader& b) {
  Proximity m;
  m.a = b.name("robot a", false);
  m.b = b.name("robot b", false);
  if (m.a == m.b) b.fail("a proximity event names robot '" + m.a + "' twice");
  m.event = b.raw().u64("event id");
  m.a_stamp = b.stamp("stamp a");
  m.b_stamp = b.stamp("stamp b");
  return m;
}

Body read_offer(BodyReader& b) {
  Offer m;
  m.encounter = b.raw().u64("encounter id");
  m.stamp = b.finite("scan stamp");
  m.pose = b.pose("pose");
  m.points = b.points("scan points");
  m.surroundings = b.points("surroundings");
  m.wide_surroundings = b.points("wide surroundings");
  const std::uint32_t n = b.count("inventory", b.limits().max_inventory, 16);
  for (std::uint32_t i = 0; i < n; ++i) {
    LayerVersion l;
    l.origin = b.name("layer origin", false);
    l.version = b.raw().u64("layer version");
    l.hops = b.raw().i32("layer hops");
    if (l.hops < 0) b.fail(fmt::format("layer '{}' has a negative hop count", l.origin));
    m.inventory.push_back(std::move(l));
  }
  return m;
}

Body read_decline(BodyReader& b) {
  Decline m;
  m.encounter = b.raw().u64("encounter id");
  m.reason = b.text("reason", b.limits().max_text);
  return m;
}

Body read_placement(BodyReader& b) {
  Placement m;
  m.encounter = b.raw().u64("encounter id");
  PeerPlacement& p = m.placement;
  p.valid = b.flag("valid");
  p.located.best = b.hypothesis();
  if (b.flag("runner-up")) p.located.runner_up = b.hypothesis();
  p.located.evaluations = b.raw().i32("evaluations");
  if (p.located.evaluations < 0) b.fail("negative evaluation count");
  if (b.flag("wide")) p.wide = b.pose("wide placement");
  if (b.flag("known transform")) m.known_transform = b.pose("known transform");
  const std::uint32_t n = b.count("pending transforms", b.limits().max_confirmations, 24);
  for (std::uint32_t i = 0; i < n; ++i) m.pending.push_back(b.pose("pending transform"));
  m.compute_ms = b.in_range("compute ms", 0.0, 1e9);
  return m;
}

Body read_chunk(BodyReader& b) {
  Chunk m;
  m.encounter = b.raw().u64("encounter id");
  m.index = b.raw().u32("chunk index");
  m.count = b.raw().u32("chunk count");
  m.total_bytes = b.raw().u64("transfer bytes");
  m.total_crc = b.raw().u32("transfer checksum");
  const std::uint32_t n = b.raw().u32("chunk bytes");
  const auto data = b.raw().take(n, "chunk data");
  m.data.assign(data.begin(), data.end());
  if (m.count > b.limits().max_chunks) b.fail(fmt::format("{} chunks, at most {} allowed", m.count, b.limits().max_chunks));
  if (m.total_bytes > b.limits().max_transfer_bytes)
    b.fail(fmt::format("a transfer of {} bytes, at most {} allowed", m.total_bytes, b.limits().max_transfer_bytes));
  if (m.count == 0 ? (m.index != 0 || m.total_bytes != 0 || n != 0) : m.index >= m.count)
    b.fail(fmt::format("chunk {} of {} is out of range", m.index, m.count));
  if (n > m.total_bytes) b.fail(fmt::format("a chunk of {} bytes in a transfer of {}", n, m.total_bytes));
  return m;
}

Body read_moved(BodyReader& b) {
  Moved m;
  m.moves.revision = b.raw().u64("revision");
  const std::uint32_t n = b.count("submap poses", b.limits().max_pieces, 28);
  std::set<std::int32_t> ids;
  for (std::uint32_t i = 0; i < n; ++i) {
    PiecePose p;
    p.id = b.raw().i32("submap id");
    p.pose = b.pose("submap pose");
    if (!ids.insert(p.id).second) b.fail(fmt::format("submap {} is listed twice", p.id));
    m.moves.pieces.push_back(p);
  }
  const std::uint32_t k = b.count("encounter poses", b.limits().max_ties, 56);
  for (std::uint32_t i = 0; i < k; ++i) {
    TieMove t;
    t.encounter = b.raw().u64("encounter id");
    t.then = b.pose("encounter pose then");
    t.now = b.pose("encounter pose now");
    m.moves.ties.push_back(t);
  }
  if (b.raw().remaining() == 0) return m;  // from an agent before loop closures travelled (2026-12-07)
  const std::uint32_t c = b.count("loop closures", b.limits().max_closures, 52);
  for (std::uint32_t i = 0; i < c; ++i) {
    PeerClosure closure;
    closure.submap = b.raw().i32("closure submap id");
    closure.in_cells = b.pose("closure pose in the submap");
    closure.node = b.pose("closure node pose");
    m.moves.closures.push_back(closure);
  }
  return m;
}

Body read_body(Kind kind, BodyReader& b) {
  switch (kind) {
    case Kind::heartbeat: return read_heartbeat(b);
    case Kind::proximity: return read_proximity(b);
    case Kind::offer: return read_offer(b);
    case Kind::decline: return read_decline(b);
    case Kind::placement: return read_placement(b);
    case Kind::chunk: return read_chunk(b);
    case Kind::moved: return read_moved(b);
  }
  b.fail(fmt::format("unknown message kind {}", static_cast<int>(kind)));
}

bool known_kind(std::uint8_t k) { return k >= static_cast<std::uint8_t>(Kind::heartbeat) && k <= static_cast<std::uint8_t>(Kind::moved); }

Message decode_checked(std::span<const std::uint8_t> bytes, const WireLimits& limits) {
  if (bytes.size() < kMinMessageBytes)
    throw ProtocolError(fmt::format("message of {} bytes is shorter than any message ({})", bytes.size(), kMinMessageBytes));
  if (bytes.size() > limits.max_message_bytes)
    throw ProtocolError(fmt::format("message of {} bytes exceeds the limit of {}", bytes.size(), limits.max_message_bytes));
  if (!std::equal(kMagic.begin(), kMagic.end(), bytes.begin())) throw ProtocolError("not a dsswarm message (bad magic)");
  const auto body_and_header = bytes.first(bytes.size() - 4);
  ByteReader tail(bytes.last(4), "message", "checksum");
  ByteReader r(body_and_header, "message", "header");
  r.take(kMagic.size(), "magic");
  const std::uint16_t version = r.u16("protocol version");
  if (version != kProtocolVersion)
    throw ProtocolError(fmt::format("protocol version {} (this agent speaks {})", version, kProtocolVersion));
  if (tail.u32("checksum") != crc_of(body_and_header)) throw ProtocolError("checksum mismatch: the message is corrupt");
  const std::uint8_t kind = r.u8("kind");
  if (!known_kind(kind)) throw ProtocolError(fmt::format("unknown message kind {}", kind));
  Message m;
  const auto k = static_cast<Kind>(kind);
  BodyReader header(r, limits, "message");
  m.header.sender = header.name("sender", false);
  m.header.recipient = header.name("recipient", true);
  m.header.incarnation = r.u64("incarnation");
  m.header.sequence = r.u64("sequence");
  const std::uint32_t body_bytes = r.u32("body size");
  if (body_bytes != r.remaining())
    throw ProtocolError(fmt::format("{} from {}: body size {} but {} bytes follow", kind_name(k),
                                    m.header.sender, body_bytes, r.remaining()));
  BodyReader body(r, limits, fmt::format("{} from {}", kind_name(k), m.header.sender));
  m.body = read_body(k, body);
  if (r.remaining() != 0) body.fail(fmt::format("{} unexpected bytes after the body", r.remaining()));
  return m;
}

}  // namespace

const char* kind_name(Kind kind) {
  switch (kind) {
    case Kind::heartbeat: return "heartbeat";
    case Kind::proximity: return "proximity";
    case Kind::offer: return "offer";
    case Kind::decline: return "decline";
    case Kind::placement: return "placement";
    case Kind::chunk: return "chunk";
    case Kind::moved: return "moved";
  }
  return "unknown";
}

Kind kind_of(const Body& body) {
  return std::visit(
      [](const auto& m) {
        using T = std::decay_t<decltype(m)>;
        if constexpr (std::is_same_v<T, Heartbeat>) return Kind::heartbeat;
        else if constexpr (std::is_same_v<T, Proximity>) return Kind::proximity;
        else if constexpr (std::is_same_v<T, Offer>) return Kind::offer;
        else if constexpr (std::is_same_v<T, Decline>) return Kind::decline;
        else if constexpr (std::is_same_v<T, Placement>) return Kind::placement;
        else if constexpr (std::is_same_v<T, Chunk>) return Kind::chunk;
        else return Kind::moved;
      },
      body);
}

std::vector<std::uint8_t> encode(const Message& message) {
  ByteWriter body;
  std::visit([&](const auto& m) { put_body(body, m); }, message.body);
  ByteWriter w;
  w.reserve(64 + body.bytes().size());
  for (const char c : kMagic) w.u8(static_cast<std::uint8_t>(c));
  w.u16(kProtocolVersion);
  w.u8(static_cast<std::uint8_t>(kind_of(message.body)));
  w.str(message.header.sender);
  w.str(message.header.recipient);
  w.u64(message.header.incarnation);
  w.u64(message.header.sequence);
  w.u32(static_cast<std::uint32_t>(body.bytes().size()));
  w.bytes().insert(w.bytes().end(), body.bytes().begin(), body.bytes().end());
  w.u32(crc_of(w.bytes()));
  return std::move(w.bytes());
}

Message decode(std::span<const std::uint8_t> bytes, const WireLimits& limits) {
  try {
    return decode_checked(bytes, limits);
  } catch (const ProtocolError&) {
    throw;
  } catch (const InputError& e) {  // the byte reader ran past the end
    throw ProtocolError(e.what());
  }
}

}  // namespace dsswarm::protocol
