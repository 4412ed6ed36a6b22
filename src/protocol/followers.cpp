#include "protocol/followers.hpp"

namespace dsswarm::protocol {

void Followers::add(const std::string& peer, const TieScan& tie) {
  std::vector<TieScan>& ties = followers_[peer].ties;
  ties.push_back(tie);
  if (ties.size() > max_ties_) ties.erase(ties.begin(), ties.end() - static_cast<std::ptrdiff_t>(max_ties_));
}

std::vector<std::string> Followers::due(std::uint64_t revision, double now, bool force) const {
  std::vector<std::string> out;
  if (revision == 0) return out;  // loop closing never moved anything
  for (const auto& [peer, f] : followers_) {
    if (f.ever_told && f.told_revision >= revision) continue;
    if (force || !f.ever_told || now - f.told_at >= interval_) out.push_back(peer);
  }
  return out;
}

const std::vector<TieScan>& Followers::ties(const std::string& peer) const {
  static const std::vector<TieScan> none;
  const auto it = followers_.find(peer);
  return it == followers_.end() ? none : it->second.ties;
}

void Followers::told(const std::string& peer, std::uint64_t revision, double now) {
  Follower& f = followers_[peer];
  f.told_revision = revision;
  f.told_at = now;
  f.ever_told = true;
}

void Followers::untold(const std::string& peer) {
  const auto it = followers_.find(peer);
  if (it != followers_.end()) it->second.ever_told = false;
}

bool Followers::newer(const std::string& sender, std::uint64_t incarnation, std::uint64_t revision) {
  const auto it = heard_.find(sender);
  if (it != heard_.end() && (incarnation < it->second.first ||
                             (incarnation == it->second.first && revision <= it->second.second)))
    return false;
  heard_[sender] = {incarnation, revision};
  return true;
}

}  // namespace dsswarm::protocol
