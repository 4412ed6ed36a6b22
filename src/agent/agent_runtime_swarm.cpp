// AgentRuntime's swarm side: the swarm thread (messages, the encounter
// engine, time-outs), proximity events and the heartbeat thread. The scan
// loop, reports and checkpoints are in agent_runtime.cpp.
#include "agent/agent_runtime.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>

namespace dsswarm::agent {
namespace {

using namespace std::chrono_literals;

// Messages held for one encounter whose scan has not come yet: an offer and a
// placement at most in a well-behaved exchange.
constexpr std::size_t kMaxHeldPerEncounter = 64;

std::uint64_t encounter_of(const protocol::Body& body) {
  if (const auto* o = std::get_if<protocol::Offer>(&body)) return o->encounter;
  if (const auto* p = std::get_if<protocol::Placement>(&body)) return p->encounter;
  if (const auto* c = std::get_if<protocol::Chunk>(&body)) return c->encounter;
  if (const auto* d = std::get_if<protocol::Decline>(&body)) return d->encounter;
  return 0;
}

}  // namespace

void AgentRuntime::swarm_loop() {
  while (!stop_swarm_.load()) {
    std::vector<std::vector<std::uint8_t>> arrived = link_.receive(50ms);
    const double t = swarm_now();
    // Peers are judged by what had arrived by now: handling this batch may
    // take a while (placing a peer's scan), and their heartbeats wait meanwhile.
    const double received_at = now();
    std::lock_guard lock(engine_mutex_);
    for (const std::vector<std::uint8_t>& bytes : arrived) {
      protocol::MessageGate::Verdict v = gate_.admit(bytes);
      if (!v.rejected.empty()) ++messages_rejected_;
      if (!v.rejected.empty()) warnings_.note(fmt::format("{}: message refused: {}", options_.name, v.rejected));
      if (!v.message) continue;
      if (v.peer_restarted) {
        sends_.forget(v.message->header.sender);
        engine_->drop_peer(v.message->header.sender, v.message->header.sender + " restarted", t);
      }
      handle(*v.message, bytes.size(), t);
    }
    std::vector<Trigger> fired;
    {
      std::lock_guard tl(trigger_mutex_);
      fired.swap(fired_);
    }
    for (const Trigger& f : fired) start_encounter(f.peer, f.encounter, t);
    engine_->tick(t);
    drop_silent_peers(received_at);
    flush_engine();
  }
}

void AgentRuntime::handle(const protocol::Message& m, std::size_t bytes, double t) {
  const std::string& from = m.header.sender;
  if (const auto* h = std::get_if<protocol::Heartbeat>(&m.body)) {
    peers_[from] = Peer{h->status, now(), false};  // (≥ received_at: it was in the batch)
    return;
  }
  if (const auto* p = std::get_if<protocol::Proximity>(&m.body)) {
    on_proximity(*p, t);
    return;
  }
  if (std::holds_alternative<protocol::Moved>(m.body)) {
    ++moved_received_;
    moved_bytes_received_ += bytes;
  }
  const std::uint64_t id = encounter_of(m.body);
  {
    std::lock_guard tl(trigger_mutex_);
    if (triggers_.armed(from, id)) {  // our view is not taken yet: it waits for its scan
      auto& held = held_[{from, id}];
      if (held.size() < kMaxHeldPerEncounter) held.emplace_back(m, bytes);  // beyond: the exchange times out
      return;
    }
  }
  engine_->receive(m, bytes, t);
}

bool AgentRuntime::arm_unless_now(const protocol::Proximity& p) {
  if (p.a != options_.name && p.b != options_.name) return true;
  const bool am_a = p.a == options_.name;
  const double stamp = am_a ? p.a_stamp : p.b_stamp;
  if (std::isnan(stamp)) return false;
  std::lock_guard tl(trigger_mutex_);
  fire(triggers_.arm({am_a ? p.b : p.a, p.event, stamp, SteadyClock::now(), false}));
  return true;
}

void AgentRuntime::on_proximity(const protocol::Proximity& p, double t) {
  if (!arm_unless_now(p)) start_encounter(p.a == options_.name ? p.b : p.a, p.event, t);
}

void AgentRuntime::raise_proximity(const protocol::Proximity& p) {
  // A stamped event only arms a trigger: it must not wait for the engine,
  // which the swarm thread holds while it places a peer's scan (seconds): the
  // scan the event names would pass meanwhile and the robot join late, from
  // another view than the in-process swarm's.
  if (arm_unless_now(p)) return;
  std::lock_guard lock(engine_mutex_);
  on_proximity(p, swarm_now());
}

void AgentRuntime::start_encounter(const std::string& peer, std::uint64_t id, double t) {
  {
    std::lock_guard lock(report_mutex_);
    event_time_.emplace(id, now());  // wall time: latencies are the robot's
  }
  engine_->start(peer, id, t);
  if (auto it = held_.find({peer, id}); it != held_.end()) {
    for (const auto& [message, bytes] : it->second) engine_->receive(message, bytes, t);
    held_.erase(it);
  }
}

void AgentRuntime::flush_engine() {
  const double t = swarm_now();
  sends_.retry(link_, t);
  for (protocol::Outgoing& out : engine_->take_outbox()) sends_.send(link_, out.recipient, std::move(out.bytes), t);
  // An exchange that lost a message cannot finish: end it now rather than
  // hold a slot until it times out.
  for (const auto& [peer, why] : sends_.take_given_up()) engine_->drop_peer(peer, why, t);
  for (protocol::EncounterOutcome& o : engine_->take_outcomes()) {
    using End = protocol::EncounterOutcome::End;
    if (o.end == End::accepted || o.end == End::rejected) ++decided_;
    if (o.end == End::accepted) {
      ++accepted_;
      last_merge_ = now();
    }
    spdlog::info("{}: encounter {} with {}: {}{}", options_.name, o.encounter, o.peer,
                 o.end == End::accepted ? "accepted" : "not merged", o.reason.empty() ? "" : " (" + o.reason + ")");
    std::lock_guard lock(report_mutex_);
    report_.outcomes.push_back(std::move(o));
  }
  open_encounters_ = engine_->open_encounters();
}

void AgentRuntime::drop_silent_peers(double wall) {
  for (auto& [name, peer] : peers_) {
    if (peer.lost || wall - peer.last_heard <= options_.peer_timeout) continue;
    peer.lost = true;
    sends_.forget(name);
    engine_->drop_peer(name, fmt::format("no heartbeat from {} for {:.0f} s", name, options_.peer_timeout),
                       swarm_now());
  }
}

void AgentRuntime::heartbeat_loop() {
  const auto period = std::chrono::duration<double>(options_.heartbeat_period);
  std::uint64_t processed_before = processed_.load();
  auto last = SteadyClock::now();
  while (!stop_swarm_.load()) {
    const protocol::Message m = heartbeats_.stamp("", protocol::Heartbeat{status(now())});
    link_.send("", protocol::encode(m));
    const auto wake = last + std::chrono::duration_cast<SteadyClock::duration>(period);
    while (!stop_swarm_.load() && SteadyClock::now() < wake) std::this_thread::sleep_for(10ms);
    const auto t = SteadyClock::now();
    const std::uint64_t processed = processed_.load();
    rate_ = static_cast<double>(processed - processed_before) / std::chrono::duration<double>(t - last).count();
    processed_before = processed;
    last = t;
  }
}

}  // namespace dsswarm::agent
