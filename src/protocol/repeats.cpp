#include "protocol/repeats.hpp"

#include <cmath>

namespace dsswarm::protocol {

void RepeatGuard::decided(const std::string& peer, std::uint64_t id, Offered a, Offered b) {
  last_[peer] = {id, std::move(a), std::move(b)};
}

std::optional<std::uint64_t> RepeatGuard::repeats(const std::string& peer, const Offered& a, const Offered& b) const {
  const auto it = last_.find(peer);
  if (it == last_.end() || !same(it->second.a, a) || !same(it->second.b, b)) return std::nullopt;
  return it->second.id;
}

bool RepeatGuard::same(const Offered& then, const Offered& now) const {
  const Pose2 d = between(then.pose, now.pose);
  return then.inventory == now.inventory && std::hypot(d.x, d.y) <= xy_ && std::abs(normalize_angle(d.theta)) <= theta_;
}

}  // namespace dsswarm::protocol
