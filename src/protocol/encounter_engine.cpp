#include "protocol/encounter_engine.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "common/hash.hpp"
#include "common/rng.hpp"
#include "protocol/confirmation.hpp"
#include "protocol/encounter_exchange.hpp"

namespace dsswarm::protocol {
namespace {

EncounterView view_of(const Offer& offer) {
  EncounterView v;
  v.pose = offer.pose;
  v.points = offer.points;
  v.surroundings = offer.surroundings;
  v.wide_surroundings = offer.wide_surroundings;
  return v;
}

}  // namespace

EncounterEngine::EncounterEngine(std::string self, const SwarmConfig& config, AgentPort& port,
                                 std::uint64_t incarnation)
    : self_(std::move(self)),
      config_(config),
      port_(port),
      stamper_(self_, incarnation),
      followers_(config.moves_interval, config.max_followed_encounters),
      repeats_(config.repeat_xy, config.repeat_theta, config.repeat_retries) {
  config_.validate();
  config_.encounter.wide_fit_settles_only = config_.slam.loop_closure.enabled;
}

EncounterEngine::~EncounterEngine() = default;

std::size_t EncounterEngine::buffered_bytes() const {
  std::size_t n = 0;
  for (const auto& [key, x] : open_) n += x->incoming.bytes_received();
  return n;
}

std::uint64_t EncounterEngine::seed_for(const Exchange& x) const {
  const std::string& a = x.self_is_a ? self_ : x.peer;
  const std::string& b = x.self_is_a ? x.peer : self_;
  return stream_seed(stream_seed(config_.slam.seed, fnv1a64(a + '\n' + b)), x.id);
}

void EncounterEngine::send(Exchange* x, const std::string& recipient, Body body) {
  Outgoing out{recipient, encode(stamper_.stamp(recipient, std::move(body)))};
  if (x) x->outcome.bytes_sent += out.bytes.size();
  outbox_.push_back(std::move(out));
}

void EncounterEngine::start(const std::string& peer, std::uint64_t encounter, double now) {
  join(peer, encounter, now);
  resume_waiting(now);
}

bool EncounterEngine::blocked(std::uint64_t encounter) const {
  return std::any_of(open_.begin(), open_.end(), [&](const auto& entry) { return entry.first.second < encounter; });
}

EncounterEngine::Exchange* EncounterEngine::join(const std::string& peer, std::uint64_t encounter, double now) {
  if (peer == self_) return nullptr;
  const Key key{peer, encounter};
  if (auto it = open_.find(key); it != open_.end()) return it->second.get();
  if (waiting_.contains(key)) return nullptr;
  if (ended_.contains(key)) {  // e.g. a restarted peer offering it again: it ends once
    send(nullptr, peer, Decline{encounter, fmt::format("encounter {} has ended for {}", encounter, self_)});
    return nullptr;
  }
  if (!config_.merge) {
    decline(peer, encounter, EncounterOutcome::Decline::merging_off, "merging is off", now);
    return nullptr;
  }
  if (open_encounters() >= config_.max_open_encounters) {
    decline(peer, encounter, EncounterOutcome::Decline::busy,
            fmt::format("busy: {} encounters open", open_encounters()), now);
    return nullptr;
  }
  if (blocked(encounter)) {
    waiting_.emplace(key, Waiting{now, std::nullopt, 0});
    return nullptr;
  }
  return open(peer, encounter, now, now);
}

// Opens encounter (peer, encounter) of event time `since`; `now` is later
// when it waited for an earlier one.
EncounterEngine::Exchange* EncounterEngine::open(const std::string& peer, std::uint64_t encounter, double since,
                                                 double now) {
  const double after_merge = since - peers_[peer].last_merge;
  if (after_merge < config_.remerge_interval) {
    decline(peer, encounter, EncounterOutcome::Decline::merged_recently,
            fmt::format("merged with {} {:.1f} s ago (re-merge interval {:.0f} s)", peer, after_merge,
                        config_.remerge_interval),
            since);
    return nullptr;
  }
  std::optional<CapturedView> view = port_.capture_view(peer, encounter);
  if (!view) {
    decline(peer, encounter, EncounterOutcome::Decline::no_scan, "no scan yet", since);
    return nullptr;
  }
  auto x = std::make_unique<Exchange>();
  x->peer = peer;
  x->id = encounter;
  x->self_is_a = self_ < peer;
  x->mine = std::move(*view);
  x->progress = now;
  EncounterOutcome& o = x->outcome;
  o.encounter = encounter;
  o.self = self_;
  o.peer = peer;
  o.self_is_a = x->self_is_a;
  o.self_pose = x->mine.view.pose;
  o.self_stamp = x->mine.stamp;
  o.started = since;
  Offer offer;
  offer.encounter = encounter;
  offer.stamp = x->mine.stamp;
  offer.pose = x->mine.view.pose;
  offer.points = x->mine.view.points;
  offer.surroundings = x->mine.view.surroundings;
  offer.wide_surroundings = x->mine.view.wide_surroundings;
  offer.inventory = port_.inventory();
  x->my_inventory = offer.inventory;
  Exchange* raw = x.get();
  open_.emplace(Key{peer, encounter}, std::move(x));
  send(raw, peer, std::move(offer));
  return raw;
}

// Starts, in id order, the waiting encounters no earlier open one holds back.
void EncounterEngine::resume_waiting(double now) {
  for (;;) {
    auto next = std::min_element(waiting_.begin(), waiting_.end(),
                                 [](const auto& x, const auto& y) { return x.first.second < y.first.second; });
    if (next == waiting_.end() || blocked(next->first.second)) return;
    const Key key = next->first;
    Waiting w = std::move(next->second);
    waiting_.erase(next);
    Exchange* x = open(key.first, key.second, w.since, now);
    if (x && w.offer) take_offer(*x, *w.offer, w.offer_bytes, now);
  }
}

void EncounterEngine::receive(const Message& message, std::size_t wire_bytes, double now) {
  const std::string& from = message.header.sender;
  if (const auto* m = std::get_if<Proximity>(&message.body)) {
    if (m->a == self_) start(m->b, m->event, now);
    else if (m->b == self_) start(m->a, m->event, now);
  } else if (const auto* o = std::get_if<Offer>(&message.body)) {
    on_offer(from, *o, wire_bytes, now);
  } else if (const auto* p = std::get_if<Placement>(&message.body)) {
    on_placement(from, *p, wire_bytes, now);
  } else if (const auto* c = std::get_if<Chunk>(&message.body)) {
    on_chunk(from, *c, wire_bytes, now);
  } else if (const auto* d = std::get_if<Decline>(&message.body)) {
    on_decline(from, *d, wire_bytes, now);
  } else if (const auto* mv = std::get_if<Moved>(&message.body)) {
    if (followers_.newer(from, message.header.incarnation, mv->moves.revision)) port_.follow(from, mv->moves);
  }
  // Heartbeats are the agent's business.
  resume_waiting(now);
}

void EncounterEngine::on_offer(const std::string& peer, const Offer& offer, std::size_t bytes, double now) {
  // An offer is also an invitation: the proximity event may not have reached us.
  Exchange* x = join(peer, offer.encounter, now);
  if (x) {
    take_offer(*x, offer, bytes, now);
    return;
  }
  if (auto w = waiting_.find({peer, offer.encounter}); w != waiting_.end() && !w->second.offer) {
    w->second.offer = offer;
    w->second.offer_bytes = bytes;
  }
}

void EncounterEngine::take_offer(Exchange& x, const Offer& offer, std::size_t bytes, double now) {
  if (x.offer) return;
  x.offer = offer;
  x.progress = now;
  x.outcome.bytes_received += bytes;
  x.outcome.peer_pose = offer.pose;
  x.outcome.peer_stamp = offer.stamp;
  const Offered mine{x.mine.view.pose, x.my_inventory}, theirs{offer.pose, offer.inventory};
  if (const auto last = repeats_.repeats(x.peer, x.self_is_a ? mine : theirs, x.self_is_a ? theirs : mine)) {
    const std::string reason =
        fmt::format("nothing new since encounter {}: both robots stand where they stood, on the same maps", *last);
    send(&x, x.peer, Decline{x.id, reason});
    x.outcome.decline = EncounterOutcome::Decline::unchanged;
    finish({x.peer, x.id}, EncounterOutcome::End::declined, reason, now);
    return;
  }
  const auto t0 = std::chrono::steady_clock::now();
  // A places B with the pair's seed, B places A with the next one.
  x.my_placement = locate_peer(x.mine.view, view_of(offer), config_.encounter, seed_for(x) + (x.self_is_a ? 0 : 1));
  x.outcome.compute_ms = ms_since(t0);
  if (std::optional<Pose2> known = port_.known_frame(x.peer))
    x.my_known = x.self_is_a ? *known : known->inverse();  // as B's frame in A's
  x.my_pending = peers_[x.peer].pending;
  send(&x, x.peer, Placement{offer.encounter, *x.my_placement, x.my_known, x.my_pending, x.outcome.compute_ms});
  if (x.their_placement) decide(x, now);
}

void EncounterEngine::on_placement(const std::string& peer, const Placement& placement, std::size_t bytes,
                                   double now) {
  auto it = open_.find({peer, placement.encounter});
  if (it == open_.end() || it->second->their_placement) return;
  Exchange& x = *it->second;
  x.their_placement = placement;
  x.outcome.bytes_received += bytes;
  x.outcome.peer_compute_ms = placement.compute_ms;
  if (x.my_placement) decide(x, now);
}

void EncounterEngine::decide(Exchange& x, double now) {
  const PeerPlacement& mine = *x.my_placement;
  const PeerPlacement& theirs = x.their_placement->placement;
  EncounterOutcome& o = x.outcome;
  o.estimate = decide_encounter(x.a_pose(), x.b_pose(), x.self_is_a ? mine : theirs, x.self_is_a ? theirs : mine,
                                config_.encounter);
  o.decided = x.decided = true;
  // Held pending, it is as good as verified: never repeated, or a repeat could confirm it.
  const bool held = config_.confirm && config_.confirm_by_directions && confirm_by_directions(x);
  const Offered offered{x.mine.view.pose, x.my_inventory}, received{x.offer->pose, x.offer->inventory};
  repeats_.decided(x.peer, x.id, x.self_is_a ? offered : received, x.self_is_a ? received : offered,
                   o.estimate.accepted || held);
  x.accepted = o.estimate.accepted;
  o.reason = o.estimate.reason;
  if (x.accepted && config_.confirm && o.confirmed_by.empty()) confirm(x);
  // A merge settles what was pending: held before it, on maps that have
  // moved since, a transform confirms no later encounter (docs/design.md).
  if (x.accepted) peers_[x.peer].pending.clear();
  if (!x.accepted) {
    finish({x.peer, x.id}, EncounterOutcome::End::rejected, o.reason, now);
    return;
  }
  send_transfer(x);
  if (x.incoming.complete()) absorb_transfer(x, now);
}

// The pending lists travel in the placements, so both robots see the same
// ones here; A's list is taken first on both sides. True when the encounter
// is held pending: only with loop closure on, where a merge becomes a
// constraint that later closures and followers refine. Without it a merge
// is final, so only verified transforms are held (and merged on).
bool EncounterEngine::confirm_by_directions(Exchange& x) {
  EncounterOutcome& o = x.outcome;
  const Placement& theirs = *x.their_placement;
  const std::vector<Pose2>& a_pending = x.self_is_a ? x.my_pending : theirs.pending;
  const std::vector<Pose2>& b_pending = x.self_is_a ? theirs.pending : x.my_pending;
  const std::optional<Pose2> t =
      pending_confirmed_by_directions(o.estimate, x.b_pose(), a_pending, b_pending, confirm_tolerance());
  if (!t) {
    if (!config_.slam.loop_closure.enabled) return false;
    const std::optional<Pose2> held = near_agreeing_estimate(o.estimate, x.b_pose(), confirm_tolerance());
    if (!held) return false;
    hold_pending(x.peer, *held);
    o.estimate.reason += "; held until a second encounter agrees";
    return true;
  }
  o.estimate.accepted = true;
  o.estimate.reason.clear();
  o.estimate.b_frame_in_a = o.estimate.b_frame_in_a_near = *t;
  o.confirmed_by = "earlier encounter, by each direction of this one";
  return false;
}

void EncounterEngine::confirm(Exchange& x) {
  EncounterOutcome& o = x.outcome;
  const Pose2 t = o.estimate.b_frame_in_a;
  auto agrees = [&](const Pose2& other) { return agrees_at_b(t, other, x.b_pose(), confirm_tolerance()); };
  // What either robot holds, so both come to the same answer.
  const Placement& theirs = *x.their_placement;
  const bool by_known = (x.my_known && agrees(*x.my_known)) || (theirs.known_transform && agrees(*theirs.known_transform));
  const bool by_earlier = std::any_of(x.my_pending.begin(), x.my_pending.end(), agrees) ||
                          std::any_of(theirs.pending.begin(), theirs.pending.end(), agrees);
  if (by_known || by_earlier) {
    o.confirmed_by = by_known ? "known transform" : "earlier encounter";
    return;
  }
  hold_pending(x.peer, t);
  x.accepted = false;
  o.reason = "unconfirmed: the placements verify; the maps merge once a second encounter agrees";
}

void EncounterEngine::hold_pending(const std::string& peer, const Pose2& t) {
  std::vector<Pose2>& pending = peers_[peer].pending;
  pending.push_back(t);
  if (pending.size() > config_.max_pending_confirmations) pending.erase(pending.begin());
}

}  // namespace dsswarm::protocol
