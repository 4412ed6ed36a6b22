#include "agent/shared_agent.hpp"

#include <algorithm>
#include <utility>

namespace dsswarm::agent {

SharedAgent::SharedAgent(std::unique_ptr<SwarmAgent> agent, const RelativePoseConfig& locate)
    : agent_(std::move(agent)),
      locate_(locate),
      composer_([this] { compose_loop(); }) {}

SharedAgent::~SharedAgent() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_composer_.notify_all();
  composer_.join();
}

void SharedAgent::restore_trajectory(Trajectory earlier) {
  std::lock_guard lock(mutex_);
  trajectory_.insert(trajectory_.begin(), earlier.begin(), earlier.end());
}

SlamStep SharedAgent::process(const LaserScan& scan) {
  std::lock_guard lock(mutex_);
  SlamStep step = agent_->process(scan);
  trajectory_.push_back({scan.timestamp, step.pose});
  // Dropped scans' poses revised after the fact (the first index is this run's).
  const std::size_t base = trajectory_.size() - 1 - step.index;
  for (const PoseRevision& r : step.revised) trajectory_[base + r.index].pose = r.pose;
  return step;
}

void SharedAgent::finish() {
  std::lock_guard lock(mutex_);
  agent_->finish();
}

Trajectory SharedAgent::optimized_trajectory() const {
  Trajectory t = trajectory_;
  // This run's scans are the last ones (an earlier run's come first).
  const std::vector<Pose2> optimized = agent_->slam().trajectory();
  const std::size_t base = t.size() >= optimized.size() ? t.size() - optimized.size() : 0;
  for (std::size_t k = 0; k < optimized.size() && base + k < t.size(); ++k) t[base + k].pose = optimized[k];
  return t;
}

SharedAgent::Staged SharedAgent::capture_locked() const {
  // The engine works on the view while scans keep changing the map: it gets
  // its own frozen copy.
  const MultiResMap& placed_in = agent_->placement_map();
  const MultiResMap& own = agent_->slam().own_map();
  auto map = std::make_shared<const MultiResMap>(placed_in);
  const bool own_only = &placed_in == &own;
  Staged s{{agent_->view(locate_), agent_->last_scan()->timestamp, map,
            own_only ? map : std::make_shared<const MultiResMap>(own), agent_->own_version(),
            agent_->loop_closing() ? std::make_shared<const MapLayer>(agent_->own_layer()) : nullptr},
           own_only ? std::vector<LayerVersion>{} : agent_->working_layers(), own_only && agent_->loop_closing()};
  s.view.view.map = map.get();
  return s;
}

// An encounter sees every merge of the encounters before it, also one not yet
// in use (SwarmAgent::fresher_placement_map, as in one process). The view
// taken at the scan may lack a merge that came in since: then its map is
// composed again, from the own map at the scan and what the robot knows now.
// The composing is the swarm thread's, off the scan path.
protocol::CapturedView SharedAgent::up_to_date(Staged staged) const {
  if (staged.own_only) return std::move(staged.view);
  std::vector<MapLayer> layers;
  {
    std::lock_guard lock(mutex_);
    layers = agent_->knowledge().layers();
  }
  auto map = SwarmAgent::composed_if_behind(*staged.view.own, staged.layers, layers);
  if (!map) return std::move(staged.view);
  staged.view.view.map = map.get();
  staged.view.keep_alive = map;
  return std::move(staged.view);
}

void SharedAgent::stage_view(const std::string& peer, std::uint64_t encounter) {
  std::lock_guard lock(mutex_);
  if (!agent_->last_scan()) return;
  std::erase_if(staged_, [&](const auto& entry) { return entry.first.first == peer; });  // one per peer suffices
  staged_[{peer, encounter}] = capture_locked();
}

std::optional<protocol::CapturedView> SharedAgent::capture_view(const std::string& peer, std::uint64_t encounter) {
  std::optional<Staged> staged;
  {
    std::lock_guard lock(mutex_);
    if (auto it = staged_.find({peer, encounter}); it != staged_.end()) {
      staged = std::move(it->second);
      staged_.erase(it);
    } else if (agent_->last_scan()) {
      staged = capture_locked();
    }
  }
  if (!staged) return std::nullopt;
  return up_to_date(std::move(*staged));
}

MapSnapshot SharedAgent::snapshot(const protocol::CapturedView& at) {
  std::lock_guard lock(mutex_);
  // As at the view's scan, as in one process: what the peer receives does not
  // depend on how long the exchange took.
  if (at.own_layer) return agent_->knowledge().snapshot(*at.own_layer);
  if (at.own) return agent_->knowledge().snapshot(at.own, at.own_version);
  return agent_->snapshot();
}

std::vector<LayerVersion> SharedAgent::inventory() const {
  std::lock_guard lock(mutex_);
  return agent_->inventory();
}

std::optional<Pose2> SharedAgent::known_frame(const std::string& origin) const {
  std::lock_guard lock(mutex_);
  const MapLayer* l = agent_->knowledge().find(origin);
  return l ? std::optional<Pose2>(l->origin_in_holder) : std::nullopt;
}

void SharedAgent::merge(MapSnapshot snapshot, const Pose2& sender_in_self, const protocol::CapturedView& at,
                        std::uint64_t encounter) {
  std::lock_guard lock(mutex_);
  agent_->tie(snapshot.sender, at.view.scan_index, at.view.pose, sender_in_self, encounter);
  if (!agent_->absorb(snapshot, sender_in_self)) return;
  agent_->schedule_merge(encounter, at.stamp, at.own, at.own_version);
  wake_composer_.notify_all();
}

std::uint64_t SharedAgent::graph_revision() const {
  std::lock_guard lock(mutex_);
  return agent_->graph_revision();
}

MapMoves SharedAgent::map_moves(const std::string& peer, const std::vector<TieScan>& ties,
                                std::size_t max_closures) const {
  std::lock_guard lock(mutex_);
  return agent_->moves(peer, ties, max_closures);
}

void SharedAgent::follow(const std::string& peer, const MapMoves& moves) {
  std::lock_guard lock(mutex_);
  agent_->follow(peer, moves);
}

bool SharedAgent::composing() const {
  std::lock_guard lock(mutex_);
  return agent_->merges_pending();
}

void SharedAgent::compose_loop() {
  std::unique_lock lock(mutex_);
  for (;;) {
    wake_composer_.wait(lock, [&] { return stop_ || agent_->has_merge_job(); });
    if (stop_) return;
    std::optional<MergeSchedule::Claimed> claimed = agent_->claim_merge_job();
    lock.unlock();
    MultiResMap working = MergeSchedule::compose(claimed->job);
    lock.lock();
    agent_->merge_job_composed(claimed->ticket, std::move(working));
    composed_.emplace_back(claimed->encounter, SteadyClock::now());
  }
}

std::optional<SwarmAgent::Installed> SharedAgent::install_due(double stamp) {
  std::lock_guard lock(mutex_);
  return agent_->install_due(stamp, false);
}

std::vector<std::pair<std::uint64_t, SteadyClock::time_point>> SharedAgent::take_composed() {
  std::lock_guard lock(mutex_);
  return std::exchange(composed_, {});
}

}  // namespace dsswarm::agent
