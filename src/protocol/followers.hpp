#pragma once
// Keeping peers' copies of this robot's map in step with its loop closures
// (Moved, messages.hpp). After an accepted encounter the peer follows this
// robot: it holds its submaps and ties its own graph to this robot's scan
// there. Whenever loop closing moves them (the graph revision grows), each
// follower is told where they lie now — at most every `interval` s, so a
// robot that closes loops often does not flood the link, and always with
// the latest word, so one that is lost is made good by the next.
// On the receiving side a Moved older than one already taken from the same
// run of its sender is ignored.
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "swarm/map_snapshot.hpp"

namespace dsswarm::protocol {

class Followers {
 public:
  // `max_ties`: encounters remembered per follower, the oldest forgotten.
  Followers(double interval, std::size_t max_ties) : interval_(interval), max_ties_(max_ties) {}

  // `peer` merged this robot's map at encounter `tie`.
  void add(const std::string& peer, const TieScan& tie);
  // Followers not yet told of `revision`, and due word at `now` (all of
  // them when `force`: a run's end). None at revision 0: nothing moved.
  std::vector<std::string> due(std::uint64_t revision, double now, bool force) const;
  const std::vector<TieScan>& ties(const std::string& peer) const;
  void told(const std::string& peer, std::uint64_t revision, double now);
  // `peer` restarted or went silent: what it was told may be lost (a
  // restarted robot keeps its layers but not the closures that came with
  // them), so it is due word again at once, whether or not the map moved.
  void untold(const std::string& peer);

  // Whether a Moved from `sender` (its run `incarnation`, `revision`) is
  // newer than any taken from it; notes it if so.
  bool newer(const std::string& sender, std::uint64_t incarnation, std::uint64_t revision);

 private:
  struct Follower {
    std::vector<TieScan> ties;
    std::uint64_t told_revision = 0;
    double told_at = 0.0;
    bool ever_told = false;
  };
  double interval_;
  std::size_t max_ties_;
  std::map<std::string, Follower> followers_;
  std::map<std::string, std::pair<std::uint64_t, std::uint64_t>> heard_;  // sender -> (incarnation, revision)
};

}  // namespace dsswarm::protocol
