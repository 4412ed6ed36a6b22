#include "protocol/repeats.hpp"

#include <cmath>

namespace dsswarm::protocol {

void RepeatGuard::decided(const std::string& peer, std::uint64_t id, Offered a, Offered b, bool verified) {
  const auto it = last_.find(peer);
  const bool again = it != last_.end() && same(it->second.a, a) && same(it->second.b, b);
  const int runs = again ? it->second.runs + 1 : 1;
  last_[peer] = {id, std::move(a), std::move(b), verified, runs};
}

std::optional<std::uint64_t> RepeatGuard::repeats(const std::string& peer, const Offered& a, const Offered& b) const {
  const auto it = last_.find(peer);
  if (it == last_.end() || !same(it->second.a, a) || !same(it->second.b, b)) return std::nullopt;
  const Last& last = it->second;
  if (!last.verified && last.runs <= retries_) return std::nullopt;  // run it again
  return last.id;
}

bool RepeatGuard::same(const Offered& then, const Offered& now) const {
  const Pose2 d = between(then.pose, now.pose);
  return then.inventory == now.inventory && std::hypot(d.x, d.y) <= xy_ && std::abs(normalize_angle(d.theta)) <= theta_;
}

}  // namespace dsswarm::protocol
