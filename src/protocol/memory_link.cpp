#include "protocol/memory_link.hpp"

#include <utility>

namespace dsswarm::protocol {

class MemoryBus::Link : public SwarmLink {
 public:
  Link(std::shared_ptr<MemoryBus> bus, std::string name, std::shared_ptr<Inbox> inbox)
      : bus_(std::move(bus)), name_(std::move(name)), inbox_(std::move(inbox)) {}
  ~Link() override { bus_->detach(name_, inbox_); }

  bool send(const std::string& recipient, std::span<const std::uint8_t> bytes) override {
    return bus_->deliver(name_, recipient, bytes);
  }
  bool reachable(const std::string& recipient) override {
    std::lock_guard lock(bus_->mutex_);
    return bus_->inboxes_.contains(recipient);
  }
  std::vector<std::vector<std::uint8_t>> receive(std::chrono::milliseconds timeout) override {
    std::unique_lock lock(bus_->mutex_);
    inbox_->arrived.wait_for(lock, timeout, [&] { return !inbox_->messages.empty() || inbox_->woken; });
    inbox_->woken = false;
    return std::exchange(inbox_->messages, {});
  }
  void wake() override {
    std::lock_guard lock(bus_->mutex_);
    inbox_->woken = true;
    inbox_->arrived.notify_all();
  }

 private:
  std::shared_ptr<MemoryBus> bus_;
  std::string name_;
  std::shared_ptr<Inbox> inbox_;
};

std::unique_ptr<SwarmLink> MemoryBus::join(const std::string& name) {
  std::lock_guard lock(mutex_);
  auto inbox = std::make_shared<Inbox>();
  inboxes_[name] = inbox;
  return std::make_unique<Link>(shared_from_this(), name, std::move(inbox));
}

void MemoryBus::leave(const std::string& name) {
  std::lock_guard lock(mutex_);
  inboxes_.erase(name);
}

void MemoryBus::detach(const std::string& name, const std::shared_ptr<Inbox>& inbox) {
  std::lock_guard lock(mutex_);
  if (auto it = inboxes_.find(name); it != inboxes_.end() && it->second == inbox) inboxes_.erase(it);
}

bool MemoryBus::deliver(const std::string& from, const std::string& to, std::span<const std::uint8_t> bytes) {
  std::lock_guard lock(mutex_);
  bool any = false;
  for (auto& [name, inbox] : inboxes_) {
    if (name == from || (!to.empty() && name != to)) continue;
    any = true;
    if (loss_ > 0.0 && rng_.uniform() < loss_) {
      ++lost_;
      continue;
    }
    inbox->messages.emplace_back(bytes.begin(), bytes.end());
    inbox->arrived.notify_all();
    ++delivered_;
  }
  return any;
}

std::uint64_t MemoryBus::delivered() const {
  std::lock_guard lock(mutex_);
  return delivered_;
}

std::uint64_t MemoryBus::lost() const {
  std::lock_guard lock(mutex_);
  return lost_;
}

}  // namespace dsswarm::protocol
