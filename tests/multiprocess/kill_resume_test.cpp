// Kill -9 a robot process in the middle of a snapshot transfer: its peer
// carries on and ends with complete outputs (the encounter abandoned, the
// partial snapshot discarded); the killed robot, restarted with --resume,
// goes on from its checkpoint and merges again.
#include <gtest/gtest.h>
#include <signal.h>

#include <fmt/format.h>
#include <unistd.h>

#include <atomic>
#include <fstream>
#include <memory>
#include <thread>

#include "apps/sim_swarm_run.hpp"
#include "eval/ate.hpp"
#include "multiprocess.hpp"
#include "protocol/wire.hpp"

namespace dsswarm::mp {
namespace {

// Reads a copy of robot `inbox`'s messages (a second reader on its inbox
// topic: DDS hands every matched reader its own copy) and reports the first
// chunk of a transfer from `sender` of more than one chunk.
class TransferWatch {
 public:
  TransferWatch(int domain, const std::string& swarm, const std::string& inbox, std::string sender)
      : tap_(domain, net::swarm_partition(swarm), inbox), sender_(std::move(sender)) {}

  // Waits for such a chunk; then calls `act` at once and counts, for `after`,
  // the chunks of that transfer that still arrive.
  struct Seen {
    std::uint64_t encounter = 0;
    std::uint32_t count = 0;     // chunks in the transfer
    std::uint32_t arrived = 0;   // of which this reader got
  };
  std::optional<Seen> watch(const std::function<void()>& act, std::chrono::milliseconds timeout,
                            std::chrono::milliseconds after) {
    std::optional<Seen> seen;
    const auto until = std::chrono::steady_clock::now() + timeout;
    auto stop_counting = until;
    while (std::chrono::steady_clock::now() < (seen ? stop_counting : until)) {
      for (const std::vector<std::uint8_t>& bytes : tap_.link.receive(20ms)) {
        const auto chunk = chunk_of(bytes);
        if (!chunk) continue;
        if (!seen && chunk->count > 1) {
          act();
          seen = Seen{chunk->encounter, chunk->count, 0};
          stop_counting = std::chrono::steady_clock::now() + after;
        }
        if (seen && chunk->encounter == seen->encounter) ++seen->arrived;
      }
    }
    return seen;
  }

 private:
  std::optional<protocol::Chunk> chunk_of(const std::vector<std::uint8_t>& bytes) const {
    try {
      const protocol::Message m = protocol::decode(bytes);
      if (m.header.sender != sender_) return std::nullopt;
      if (const auto* c = std::get_if<protocol::Chunk>(&m.body)) return *c;
    } catch (const protocol::ProtocolError&) {
    }
    return std::nullopt;
  }

  SwarmTap tap_;
  std::string sender_;
};

TEST(MultiProcessFaults, KillMidTransferThenResumeFromTheCheckpoint) {
  const int domain = test_domain();
  std::unique_ptr<Rig> rig_holder;
  std::string swarm;
  fs::path config;
  double start_at = 0.0;
  std::map<std::string, std::size_t> process;
  auto agent = [&](int k, std::vector<std::string> extra) {
    SimAgent a;
    a.name = fmt::format("robot{}", k);
    a.robot = k;
    a.start_at = start_at;
    a.domain = domain;
    a.out = rig_holder->dir() / a.name;
    a.extra = {"--swarm", swarm, "--config", config.string(), "--checkpoint-period", "1", "--linger", "5"};
    a.extra.insert(a.extra.end(), extra.begin(), extra.end());
    return rig_holder->start(a.name + (extra.empty() ? "" : "_resumed"), agent_args(a));
  };
  // The kill races the sender: when robot1 has put the whole snapshot on the
  // wire before SIGKILL lands (a small snapshot, a busy machine), the run
  // proves nothing about a cut transfer and is started again (at most 3 times).
  std::optional<TransferWatch::Seen> seen;
  for (int attempt = 1; attempt <= 3; ++attempt) {
    rig_holder.reset();  // stops the last attempt's robots first: the new rig reuses its folder
    rig_holder = std::make_unique<Rig>();
    swarm = fmt::format("kill{}-{}", getpid(), attempt);
    // 1 kB chunks: a first snapshot (~150 kB with its submaps) takes ~150 messages, long enough to
    // land a kill in. The later ones (~500 kB) are more than a busy robot's inbox holds: what it
    // refuses waits and goes out later (agent/send_queue.hpp), the exchange goes on.
    config = rig_holder->dir() / "config.json";
    std::ofstream(config) << R"({"swarm": {"chunk_bytes": 1024}})";
    start_at = unix_in(3.0);
    // A second reader of robot3's inbox, gone once it has seen what it waits for:
    // a reader that stops taking holds up robot3's senders (reliable, keep-all).
    auto watch = std::make_unique<TransferWatch>(domain, swarm, "robot3", "robot1");
    for (int k = 1; k <= 3; ++k) process[fmt::format("robot{}", k)] = agent(k, {});
    seen = watch->watch([&] { rig_holder->group().signal(process["robot1"], SIGKILL); }, 60s, 1s);
    watch.reset();
    ASSERT_TRUE(seen) << "no snapshot transfer from robot1 to robot3 within 60 s";
    EXPECT_EQ(rig_holder->wait(process["robot1"], 5s), 128 + SIGKILL);
    if (seen->arrived < seen->count) break;
    std::cout << "attempt " << attempt << ": the kill came after the whole transfer had been sent (" << seen->arrived
              << " of " << seen->count << " chunks); again\n";
  }
  Rig& rig = *rig_holder;
  ASSERT_LT(seen->arrived, seen->count) << "in 3 attempts the kill always came after the whole transfer had been sent";
  std::cout << "killed robot1 in encounter " << seen->encounter << ": " << seen->arrived << " of " << seen->count
            << " chunks arrived\n";

  // What robot1 had saved when it died.
  const fs::path r1 = rig.dir() / "robot1";
  const Trajectory before = read_tum(r1 / "trajectory.tum");
  const nlohmann::json checkpoint = read_json(r1 / "checkpoint.json");
  ASSERT_GT(before.size(), 10u);
  const std::size_t resumed = agent(1, {"--resume"});

  for (const char* r : {"robot2", "robot3"}) EXPECT_EQ(rig.wait(process[r], 120s), 0) << r;
  EXPECT_EQ(rig.wait(resumed, 60s), 0);

  // The peer: complete outputs, the encounter abandoned, nothing of the partial snapshot merged.
  const SimSwarmRun sim = simulate_swarm_run({3, 1, 1, 3.0});
  const fs::path r3 = rig.dir() / "robot3";
  expect_complete_outputs(r3, sim.streams[2].scans.size());
  const auto r3_outcomes = outcomes_by_id(r3 / "encounters.json");
  ASSERT_TRUE(r3_outcomes.count(seen->encounter));
  const nlohmann::json& cut = r3_outcomes.at(seen->encounter);
  EXPECT_EQ(cut.at("end"), "abandoned") << cut.dump();
  EXPECT_EQ(cut.at("layers_received"), 0) << cut.dump();
  std::cout << "robot3's encounter " << seen->encounter << ": " << cut.at("reason").get<std::string>() << "\n";
  const Trajectory r3_track = read_tum(r3 / "trajectory.tum");
  EXPECT_LT(evaluate_ate(r3_track, sim.truth.world_poses[2]).rmse, 0.05);

  // The killed robot went on from its checkpoint: earlier poses kept, map version continued.
  const Trajectory after = read_tum(r1 / "trajectory.tum");
  ASSERT_GT(after.size(), before.size());
  for (std::size_t i = 0; i < before.size(); ++i) {
    ASSERT_DOUBLE_EQ(after[i].timestamp, before[i].timestamp) << "pose " << i;
    ASSERT_NEAR(after[i].pose.x, before[i].pose.x, 1e-6) << "pose " << i;
  }
  for (std::size_t i = 1; i < after.size(); ++i) ASSERT_GT(after[i].timestamp, after[i - 1].timestamp) << i;
  const nlohmann::json r1_stats = read_json(r1 / "stats.json");
  EXPECT_GT(r1_stats.at("map_version").get<std::uint64_t>(), checkpoint.at("own_version").get<std::uint64_t>());
  EXPECT_NE(rig.log_tail("robot1_resumed", 200).find("resuming from"), std::string::npos);

  // ... and merged again, with robot3 (both sides of a later encounter accepted).
  const auto r1_outcomes = outcomes_by_id(r1 / "encounters.json");
  bool merged_again = false;
  for (const auto& [id, o] : r1_outcomes)
    if (id > seen->encounter && o.at("peer") == "robot3" && o.at("end") == "accepted" && r3_outcomes.count(id) &&
        r3_outcomes.at(id).at("end") == "accepted")
      merged_again = true;
  EXPECT_TRUE(merged_again);
  EXPECT_TRUE(holds(read_json(r3 / "stats.json"), "robot1"));
}

}  // namespace
}  // namespace dsswarm::mp
