#include "swarm/merge_schedule.hpp"

#include <algorithm>
#include <limits>

#include "swarm/map_merge.hpp"

namespace dsswarm {

MultiResMap MergeSchedule::compose(const Job& job) { return compose_working_map(*job.own, job.foreign); }

void MergeSchedule::inserted(std::size_t version, double stamp, const Pose2& pose, const Pose2& laser_offset,
                             std::vector<ScanPoint> points) {
  if (!keeps_scans()) return;  // no job can start before it
  newest_stamp_ = inserted_.empty() ? stamp : std::max(newest_stamp_, stamp);
  inserted_.push_back({version, stamp, pose, laser_offset, std::move(points)});
  prune();
}

bool MergeSchedule::replays_from(std::size_t version, std::size_t current) const {
  if (version == current) return true;
  return version < current && !inserted_.empty() && inserted_.front().version <= version + 1 &&
         inserted_.back().version == current;
}

void MergeSchedule::add(Job job, double view_stamp, std::uint64_t encounter) {
  Entry e;
  e.ticket = next_ticket_++;
  e.job = std::move(job);
  e.due = view_stamp + delay_;
  e.encounter = encounter;
  entries_.push_back(std::move(e));
}

bool MergeSchedule::has_unclaimed() const {
  return std::any_of(entries_.begin(), entries_.end(), [](const Entry& e) { return !e.claimed && !e.working; });
}

std::optional<MergeSchedule::Claimed> MergeSchedule::claim() {
  for (Entry& e : entries_)
    if (!e.claimed && !e.working) {
      e.claimed = true;
      return Claimed{e.ticket, e.encounter, e.job};
    }
  return std::nullopt;
}

void MergeSchedule::composed(std::uint64_t ticket, MultiResMap working) {
  for (Entry& e : entries_)
    if (e.ticket == ticket) {
      e.working = std::move(working);
      e.claimed = false;
    }
}

std::optional<MergeSchedule::Due> MergeSchedule::take_due(double stamp, bool compose_here) {
  std::optional<std::size_t> take;
  for (std::size_t i = 0; i < entries_.size(); ++i) {
    Entry& e = entries_[i];
    // Due, or the log's time went back before its scan (a looped bag).
    if (e.due > stamp && stamp >= e.due - delay_) break;  // later ones are due later still
    if (e.working || compose_here) take = i;
    else e.missed = true;
  }
  if (!take) return std::nullopt;
  Entry& e = entries_[*take];
  Due due{e.working ? std::move(*e.working) : compose(e.job), {}, {}, false};
  due.layers = layer_versions(e.job.foreign);
  for (const Inserted& s : inserted_)
    if (s.version > e.job.own_version) due.working.insert_scan(s.pose, s.laser_offset, s.points);
  for (std::size_t i = 0; i <= *take; ++i) {
    due.encounters.push_back(entries_[i].encounter);
    due.late = due.late || entries_[i].missed;
  }
  entries_.erase(entries_.begin(), entries_.begin() + static_cast<std::ptrdiff_t>(*take + 1));
  prune();
  return due;
}

void MergeSchedule::prune() {
  std::size_t needed = std::numeric_limits<std::size_t>::max();  // the oldest own map a job starts from
  for (const Entry& e : entries_) needed = std::min(needed, e.job.own_version);
  while (!inserted_.empty() && inserted_.front().version <= needed &&
         (inserted_.front().stamp < newest_stamp_ - delay_ || !keeps_scans()))
    inserted_.pop_front();
}

}  // namespace dsswarm
