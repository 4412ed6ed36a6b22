// How encounters end (declined, abandoned, timed out, finished), and what
// follows a merge (followers.hpp).
#include <fmt/format.h>

#include "protocol/encounter_engine.hpp"
#include "protocol/encounter_exchange.hpp"

namespace dsswarm::protocol {

void EncounterEngine::decline(const std::string& peer, std::uint64_t encounter, EncounterOutcome::Decline why,
                              const std::string& reason, double now) {
  send(nullptr, peer, Decline{encounter, reason});
  EncounterOutcome o;
  o.encounter = encounter;
  o.self = self_;
  o.peer = peer;
  o.self_is_a = self_ < peer;
  o.end = EncounterOutcome::End::declined;
  o.decline = why;
  o.reason = reason;
  o.started = o.ended = now;
  outcomes_.push_back(std::move(o));
  remember_ended({peer, encounter});
}

void EncounterEngine::remember_ended(const Key& key) {
  if (!ended_.insert(key).second) return;
  ended_order_.push_back(key);
  if (ended_order_.size() <= config_.remembered_encounters) return;
  ended_.erase(ended_order_.front());
  ended_order_.pop_front();
}

void EncounterEngine::end_waiting(const Key& key, EncounterOutcome::End end, EncounterOutcome::Decline why,
                                  std::string reason, double now) {
  auto it = waiting_.find(key);
  if (it == waiting_.end()) return;
  EncounterOutcome o;
  o.encounter = key.second;
  o.self = self_;
  o.peer = key.first;
  o.self_is_a = self_ < key.first;
  o.end = end;
  o.decline = why;
  o.reason = std::move(reason);
  o.started = it->second.since;
  o.ended = now;
  outcomes_.push_back(std::move(o));
  remember_ended(key);
  waiting_.erase(it);
}

void EncounterEngine::on_decline(const std::string& peer, const Decline& decline, std::size_t bytes, double now) {
  end_waiting({peer, decline.encounter}, EncounterOutcome::End::declined, EncounterOutcome::Decline::by_peer,
              peer + " declined: " + decline.reason, now);
  auto it = open_.find({peer, decline.encounter});
  if (it == open_.end()) return;
  it->second->outcome.bytes_received += bytes;
  it->second->outcome.decline = EncounterOutcome::Decline::by_peer;
  finish(it->first, EncounterOutcome::End::declined, peer + " declined: " + decline.reason, now);
}

void EncounterEngine::finish(const Key& key, EncounterOutcome::End end, std::string reason, double now) {
  auto it = open_.find(key);
  if (it == open_.end()) return;
  EncounterOutcome o = std::move(it->second->outcome);
  o.end = end;
  o.ended = now;
  if (end != EncounterOutcome::End::accepted) o.reason = std::move(reason);
  outcomes_.push_back(std::move(o));
  remember_ended(key);  // before the erase: `key` may be the map's own
  open_.erase(it);
}

void EncounterEngine::drop_peer(const std::string& peer, const std::string& why, double now) {
  followers_.untold(peer);
  std::vector<Key> keys;
  for (const auto& [key, w] : waiting_)
    if (key.first == peer) keys.push_back(key);
  for (const Key& k : keys) end_waiting(k, EncounterOutcome::End::abandoned, EncounterOutcome::Decline::none, why, now);
  keys.clear();
  for (const auto& [key, x] : open_)
    if (key.first == peer) keys.push_back(key);
  for (const Key& k : keys) finish(k, EncounterOutcome::End::abandoned, why, now);
  resume_waiting(now);
}

void EncounterEngine::abandon_all(const std::string& why, double now) {
  while (!waiting_.empty())
    end_waiting(waiting_.begin()->first, EncounterOutcome::End::abandoned, EncounterOutcome::Decline::none, why, now);
  while (!open_.empty()) finish(open_.begin()->first, EncounterOutcome::End::abandoned, why, now);
}

void EncounterEngine::tick(double now) {
  struct Late {
    Key key;
    const char* stage;
    double limit;
  };
  std::vector<Late> late;
  for (const auto& [key, x] : open_) {
    const double limit = x->offer ? config_.exchange_timeout : config_.offer_timeout;
    if (now - x->progress > limit)
      late.push_back({key, !x->offer ? "offer" : !x->their_placement ? "placement" : "snapshot", limit});
  }
  for (const Late& l : late)
    finish(l.key, EncounterOutcome::End::abandoned,
           fmt::format("timed out after {:.0f} s waiting for {}'s {}", l.limit, l.key.first, l.stage), now);
  // One that waited that long for this robot's earlier encounters: the peer has given up on it.
  std::vector<Key> stale;
  for (const auto& [key, w] : waiting_)
    if (now - w.since > config_.offer_timeout) stale.push_back(key);
  for (const Key& key : stale) {
    const std::string reason =
        fmt::format("waited {:.0f} s for {}'s earlier encounters to end", config_.offer_timeout, self_);
    send(nullptr, key.first, Decline{key.second, reason});
    end_waiting(key, EncounterOutcome::End::abandoned, EncounterOutcome::Decline::none, reason, now);
  }
  resume_waiting(now);
  announce_moves(now);
}

void EncounterEngine::announce_moves(double now, bool force) {
  const std::uint64_t revision = port_.graph_revision();
  const std::vector<std::string> due = followers_.due(revision, now, force);
  for (const std::string& peer : due) {
    MapMoves moves = port_.map_moves(peer, followers_.ties(peer), config_.max_moved_closures);
    if (!moves.pieces.empty() || !moves.ties.empty()) send(nullptr, peer, Moved{std::move(moves)});
    followers_.told(peer, revision, now);
  }
}

}  // namespace dsswarm::protocol
