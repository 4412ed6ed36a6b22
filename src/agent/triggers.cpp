#include "agent/triggers.hpp"

#include <algorithm>
#include <cmath>

namespace dsswarm::agent {
namespace {

// Stamps cross ROS's sec + nanosec: equal within a microsecond.
bool same_stamp(double a, double b) { return std::abs(a - b) < 1e-6; }

}  // namespace

std::vector<Trigger> TriggerBook::arm(Trigger t) {
  if (std::any_of(recent_.begin(), recent_.end(), [&](double s) { return same_stamp(s, t.stamp); })) {
    t.late = true;
    return {std::move(t)};
  }
  armed_.push_back(std::move(t));
  return {};
}

std::vector<Trigger> TriggerBook::on_scan(double stamp) {
  recent_.push_back(stamp);
  if (recent_.size() > remembered_) recent_.pop_front();
  std::vector<Trigger> due;
  std::erase_if(armed_, [&](Trigger& t) {
    if (!same_stamp(t.stamp, stamp)) return false;
    due.push_back(std::move(t));
    return true;
  });
  return due;
}

std::vector<Trigger> TriggerBook::overdue(std::chrono::steady_clock::time_point now) {
  std::vector<Trigger> due;
  std::erase_if(armed_, [&](Trigger& t) {
    if (now - t.armed_at < patience_) return false;
    t.late = true;
    due.push_back(std::move(t));
    return true;
  });
  return due;
}

bool TriggerBook::armed(const std::string& peer, std::uint64_t encounter) const {
  return std::any_of(armed_.begin(), armed_.end(),
                     [&](const Trigger& t) { return t.peer == peer && t.encounter == encounter; });
}

}  // namespace dsswarm::agent
