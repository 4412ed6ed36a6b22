#include "protocol/gate.hpp"

#include <fmt/format.h>

namespace dsswarm::protocol {

MessageGate::Verdict MessageGate::reject(const std::string& category, std::string detail) {
  ++rejected_total_;
  ++rejected_by_reason_[category];
  Verdict v;
  v.rejected = std::move(detail);
  return v;
}

MessageGate::Verdict MessageGate::admit(std::span<const std::uint8_t> bytes) {
  Message m;
  try {
    m = decode(bytes, limits_);
  } catch (const ProtocolError& e) {
    return reject("malformed", e.what());
  }
  const Header& h = m.header;
  if (h.sender == self_) return {};
  if (!h.recipient.empty() && h.recipient != self_)
    return reject("misdirected", fmt::format("{} from {} is for {}", kind_name(kind_of(m.body)), h.sender, h.recipient));
  if (h.sequence == 0) return reject("replayed", fmt::format("{} from {} has sequence 0", kind_name(kind_of(m.body)), h.sender));
  Verdict v;
  if (!incarnations_.contains(h.sender) && incarnations_.size() >= max_senders_)
    return reject("too many senders", fmt::format("{} from {}: {} senders are known already",
                                                  kind_name(kind_of(m.body)), h.sender, max_senders_));
  std::uint64_t& newest = incarnations_[h.sender];
  if (h.incarnation < newest)
    return reject("stale", fmt::format("{} from {} belongs to an earlier run of it", kind_name(kind_of(m.body)), h.sender));
  if (h.incarnation > newest) {
    v.peer_restarted = newest != 0;
    newest = h.incarnation;
  }
  Stream& s = streams_[{h.sender, !h.recipient.empty()}];
  if (s.incarnation == h.incarnation && h.sequence <= s.sequence)
    return reject("replayed", fmt::format("{} from {}: sequence {} after {}", kind_name(kind_of(m.body)), h.sender,
                                          h.sequence, s.sequence));
  s = {h.incarnation, h.sequence};
  ++accepted_;
  v.message = std::move(m);
  return v;
}

Message MessageStamper::stamp(std::string recipient, Body body) {
  Message m;
  m.header.sender = self_;
  m.header.incarnation = incarnation_;
  m.header.sequence = ++next_[recipient];
  m.header.recipient = std::move(recipient);
  m.body = std::move(body);
  return m;
}

}  // namespace dsswarm::protocol
