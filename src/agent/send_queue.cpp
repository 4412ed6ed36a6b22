#include "agent/send_queue.hpp"

#include <fmt/format.h>

namespace dsswarm::agent {
namespace {

std::string unreachable(const std::string& recipient) {
  return fmt::format("{} cannot be reached: a message to it was not delivered (gone, or not authorized)", recipient);
}

}  // namespace

void SendQueue::send(protocol::SwarmLink& link, const std::string& recipient, std::vector<std::uint8_t> bytes,
                     double now) {
  if (given_up_.contains(recipient)) return;
  if (const auto it = waiting_.find(recipient); it != waiting_.end()) {
    it->second.messages.push_back(std::move(bytes));
    ++deferred_;
    return;
  }
  if (link.send(recipient, bytes)) return;
  if (!link.reachable(recipient)) {
    give_up(recipient, unreachable(recipient));
    return;
  }
  Waiting& w = waiting_[recipient];
  w.messages.push_back(std::move(bytes));
  w.since = now;
  ++deferred_;
}

void SendQueue::retry(protocol::SwarmLink& link, double now) {
  for (auto it = waiting_.begin(); it != waiting_.end();) {
    const std::string& recipient = it->first;
    Waiting& w = it->second;
    while (!w.messages.empty() && link.send(recipient, w.messages.front())) {
      w.messages.pop_front();
      w.since = now;
    }
    if (w.messages.empty()) {
      it = waiting_.erase(it);
      continue;
    }
    if (!link.reachable(recipient))
      give_up(recipient, unreachable(recipient));
    else if (now - w.since > patience_)
      give_up(recipient, fmt::format("{} took no message for {:.0f} s (its inbox stayed full)", recipient, patience_));
    else {
      ++it;
      continue;
    }
    it = waiting_.erase(it);
  }
}

void SendQueue::give_up(const std::string& recipient, std::string why) {
  given_up_.try_emplace(recipient, std::move(why));
}

std::vector<std::pair<std::string, std::string>> SendQueue::take_given_up() {
  std::vector<std::pair<std::string, std::string>> out(given_up_.begin(), given_up_.end());
  given_up_.clear();
  return out;
}

std::size_t SendQueue::waiting() const {
  std::size_t n = 0;
  for (const auto& [recipient, w] : waiting_) n += w.messages.size();
  return n;
}

}  // namespace dsswarm::agent
