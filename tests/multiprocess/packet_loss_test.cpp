// Two robot processes, each in its own network namespace, joined by a veth
// pair, each side dropping 10% of the UDP packets it sends (nftables; netem
// is not available here): discovery, heartbeats and the whole encounter
// exchange still get through, and the two merge. Needs root, `ip` and `nft`;
// skipped with a message otherwise. The namespaces (and with them the veth
// pair and the rules) are removed whatever happens.
#include <gtest/gtest.h>

#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <regex>

#include "apps/sim_swarm_run.hpp"
#include "multiprocess.hpp"

namespace dsswarm::mp {
namespace {

int sh(const std::string& command) { return std::system((command + " >/dev/null 2>&1").c_str()); }

std::string output_of(const std::string& command) {
  std::string out;
  if (FILE* p = ::popen(command.c_str(), "r")) {
    char buffer[4096];
    for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, p)) > 0;) out.append(buffer, n);
    ::pclose(p);
  }
  return out;
}

// Two namespaces ns[0], ns[1] with veth ends dev[0], dev[1] (10.213.K.1 and .2).
class LossyLink {
 public:
  // Empty when namespaces cannot be made here (then skip()).
  std::string why_not;
  std::string ns[2], dev[2];

  explicit LossyLink(int loss_percent) {
    if (::geteuid() != 0) {
      why_not = "needs root (ip netns, nft)";
      return;
    }
    if (sh("command -v ip") != 0 || sh("command -v nft") != 0) {
      why_not = "needs `ip` (iproute2) and `nft` (nftables): scripts/install_deps.sh";
      return;
    }
    const int id = static_cast<int>(::getpid() % 100000);
    for (int k = 0; k < 2; ++k) {
      ns[k] = fmt::format("dsswarm-loss{}-{}", id, k);
      dev[k] = fmt::format("dsl{}{}", id, k);  // interface names: at most 15 characters
    }
    if (sh("ip netns add " + ns[0]) != 0) {
      why_not = "network namespaces are not allowed here (ip netns add failed)";
      return;
    }
    made_[0] = true;
    made_[1] = sh("ip netns add " + ns[1]) == 0;
    const int subnet = id % 250;
    ok_ = made_[1] && sh(fmt::format("ip link add {} netns {} type veth peer name {} netns {}", dev[0], ns[0], dev[1], ns[1])) == 0;
    for (int k = 0; ok_ && k < 2; ++k) {
      const std::string in = "ip netns exec " + ns[k] + " ";
      ok_ = sh(in + fmt::format("ip addr add 10.213.{}.{}/24 dev {}", subnet, k + 1, dev[k])) == 0 &&
            sh(in + "ip link set lo up") == 0 && sh(in + "ip link set " + dev[k] + " up") == 0 &&
            sh(in + fmt::format("nft 'table inet loss {{ chain out {{ type filter hook output priority 0; "
                                "oifname \"{0}\" meta l4proto udp counter; "
                                "oifname \"{0}\" meta l4proto udp numgen random mod 100 < {1} counter drop; }}; }}'",
                                dev[k], loss_percent)) == 0;
    }
    if (!ok_) why_not = "could not set up the veth pair and the nftables loss rule";
  }
  ~LossyLink() {
    for (int k = 0; k < 2; ++k)
      if (made_[k]) sh("ip netns del " + ns[k]);
  }
  LossyLink(const LossyLink&) = delete;
  LossyLink& operator=(const LossyLink&) = delete;

  bool ok() const { return ok_; }
  // UDP packets namespace k has sent over its veth end, and of those dropped.
  std::pair<long, long> sent_dropped(int k) const {
    const std::string rules = output_of("ip netns exec " + ns[k] + " nft list table inet loss 2>/dev/null");
    const std::regex counter(R"(counter packets (\d+))");
    std::vector<long> n;
    for (auto it = std::sregex_iterator(rules.begin(), rules.end(), counter); it != std::sregex_iterator(); ++it)
      n.push_back(std::stol((*it)[1]));
    return n.size() == 2 ? std::pair{n[0], n[1]} : std::pair{-1L, -1L};
  }

 private:
  bool made_[2] = {false, false};
  bool ok_ = false;
};

TEST(MultiProcessFaults, TenPercentPacketLossTheExchangeStillCompletes) {
  LossyLink net(10);
  if (!net.ok()) GTEST_SKIP() << net.why_not;
  Rig rig;  // after the namespaces: its processes are stopped before they go
  const fs::path config = rig.dir() / "config.json";
  std::ofstream(config) << R"({"swarm": {"exchange_timeout": 20}})";
  const double start_at = unix_in(4.0);
  for (int k = 1; k <= 2; ++k) {
    SimAgent a;
    a.name = fmt::format("robot{}", k);
    a.robot = k;
    a.robots = 2;
    a.start_at = start_at;
    a.domain = test_domain();
    a.out = rig.dir() / a.name;
    a.interface = net.dev[k - 1];
    a.extra = {"--config", config.string(), "--linger", "5"};
    std::vector<std::string> args{"/usr/sbin/ip", "netns", "exec", net.ns[k - 1], DSSWARM_CLI};
    const std::vector<std::string> agent = agent_args(a);
    args.insert(args.end(), agent.begin(), agent.end());
    rig.start_raw(a.name, args);
  }
  for (std::size_t p = 0; p < 2; ++p) EXPECT_EQ(rig.wait(p, 120s), 0) << "robot" << p + 1;
  long sent = 0, dropped = 0;
  for (int k = 0; k < 2; ++k) {
    const auto [s, d] = net.sent_dropped(k);
    EXPECT_GT(d, 0) << net.ns[k] << ": the loss rule dropped nothing: the robots did not talk over the veth pair";
    sent += s;
    dropped += d;
  }

  const SimSwarmRun sim = simulate_swarm_run({2, 1, 1, 3.0});
  const fs::path r1 = rig.dir() / "robot1", r2 = rig.dir() / "robot2";
  expect_complete_outputs(r1, sim.streams[0].scans.size());
  expect_complete_outputs(r2, sim.streams[1].scans.size());
  const std::size_t both = accepted_by_both(r1, r2);
  EXPECT_GE(both, 1u) << "no encounter completed under 10% loss";
  const nlohmann::json s1 = read_json(r1 / "stats.json"), s2 = read_json(r2 / "stats.json");
  EXPECT_TRUE(holds(s1, "robot2")) << "robot1 lacks robot2's map";
  EXPECT_TRUE(holds(s2, "robot1")) << "robot2 lacks robot1's map";
  std::cout << "10% loss: " << dropped << " of " << sent << " UDP packets dropped; " << both
            << " encounters accepted by both\n";
}

}  // namespace
}  // namespace dsswarm::mp
