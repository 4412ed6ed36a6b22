// The snapshot transfer of an accepted encounter, and the merge.
#include <fmt/format.h>

#include "io/maps/dsmap.hpp"
#include "protocol/encounter_engine.hpp"
#include "protocol/encounter_exchange.hpp"

namespace dsswarm::protocol {
namespace {

// Whether a holder of `held` would take `layer` (as map_knowledge's supersedes,
// by version and hop count; the pose tie-break is left to the receiver).
bool peer_lacks(const MapLayer& layer, const std::vector<LayerVersion>& held) {
  for (const LayerVersion& h : held)
    if (h.origin == layer.origin)
      return layer.version > h.version || (layer.version == h.version && layer.hops + 1 < h.hops);
  return true;
}

}  // namespace

void EncounterEngine::send_transfer(Exchange& x) {
  MapSnapshot all = port_.snapshot(x.mine);
  MapSnapshot lacking;
  lacking.sender = self_;
  for (MapLayer& l : all.layers)
    if (l.origin != x.peer && peer_lacks(l, x.offer->inventory)) lacking.layers.push_back(std::move(l));
  const std::vector<std::uint8_t> bytes = lacking.layers.empty() ? std::vector<std::uint8_t>{} : encode_dsmap(lacking);
  x.outcome.snapshot_bytes_sent = bytes.size();
  for (Chunk& c : split_transfer(x.id, bytes, config_.chunk_bytes)) send(&x, x.peer, std::move(c));
}

void EncounterEngine::on_chunk(const std::string& peer, const Chunk& chunk, std::size_t bytes, double now) {
  auto it = open_.find({peer, chunk.encounter});
  if (it == open_.end()) return;  // abandoned, or never ours
  Exchange& x = *it->second;
  x.outcome.bytes_received += bytes;
  if (buffered_bytes() + chunk.data.size() > config_.max_transfer_bytes ||
      chunk.total_bytes > config_.max_transfer_bytes) {
    finish(it->first, EncounterOutcome::End::abandoned,
           fmt::format("snapshot transfers would hold more than {} MiB", config_.max_transfer_bytes >> 20), now);
    return;
  }
  try {
    if (!x.incoming.add(chunk)) return;
  } catch (const ProtocolError& e) {
    finish(it->first, EncounterOutcome::End::abandoned, std::string("bad snapshot transfer: ") + e.what(), now);
    return;
  }
  if (x.decided && x.accepted) absorb_transfer(x, now);
}

void EncounterEngine::absorb_transfer(Exchange& x, double now) {
  const Key key{x.peer, x.id};
  MapSnapshot snapshot;
  try {
    const std::vector<std::uint8_t> bytes = x.incoming.take();
    x.outcome.snapshot_bytes_received = bytes.size();
    if (!bytes.empty()) snapshot = decode_dsmap(bytes, "snapshot from " + x.peer);
  } catch (const InputError& e) {
    finish(key, EncounterOutcome::End::abandoned, std::string("bad snapshot: ") + e.what(), now);
    return;
  }
  if (!snapshot.layers.empty() && snapshot.sender != x.peer) {
    finish(key, EncounterOutcome::End::abandoned, "snapshot from " + x.peer + " names sender " + snapshot.sender, now);
    return;
  }
  snapshot.sender = x.peer;  // also when it sent nothing
  const Pose2 t = x.outcome.estimate.b_frame_in_a;
  const auto t0 = std::chrono::steady_clock::now();
  x.outcome.layers_received = snapshot.layers.size();
  port_.merge(std::move(snapshot), x.self_is_a ? t : t.inverse(), x.mine, x.id);
  followers_.add(x.peer, {x.id, x.mine.view.scan_index, x.mine.view.pose});
  x.outcome.merge_ms = ms_since(t0);
  peers_[x.peer].last_merge = x.outcome.started;  // from the event, as robots that finish at different moments agree
  finish(key, EncounterOutcome::End::accepted, "", now);
}

}  // namespace dsswarm::protocol
