#include "multiprocess.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <deque>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>
#include <thread>

#include "net/net_test_util.hpp"
#include "protocol/wire.hpp"

namespace dsswarm::mp {

int test_domain(int k) { return static_cast<int>(net::test::test_domain(k)); }

Rig::Rig() : dir_(fs::path(DSSWARM_TEST_TMP) / "multiprocess" / net::test::test_id()) {
  fs::remove_all(dir_);
  fs::create_directories(dir_ / "logs");
}

Rig::~Rig() {
  group_.stop_all(5s);
  if (testing::Test::HasFailure()) std::cout << all_logs();
  std::error_code ignored;
  if (!std::getenv("DSSWARM_KEEP_TEST_FILES")) fs::remove_all(dir_, ignored);
}

std::size_t Rig::start(const std::string& log, const std::vector<std::string>& args) {
  std::vector<std::string> argv{DSSWARM_CLI};
  argv.insert(argv.end(), args.begin(), args.end());
  return start_raw(log, argv);
}

std::size_t Rig::start_raw(const std::string& log, const std::vector<std::string>& argv) {
  if (std::find(logs_.begin(), logs_.end(), log) == logs_.end()) logs_.push_back(log);  // a log reused: appended
  return group_.start(argv, dir_ / "logs" / (log + ".log"));
}

int Rig::wait(std::size_t process, std::chrono::milliseconds timeout) {
  const std::optional<int> status = group_.wait(process, timeout);
  if (!status) ADD_FAILURE() << "process " << process << " still running after " << timeout.count() << " ms";
  return status.value_or(-1);
}

std::string Rig::log_tail(const std::string& log, std::size_t lines) const {
  std::ifstream in(dir_ / "logs" / (log + ".log"));
  std::deque<std::string> tail;
  for (std::string line; std::getline(in, line);) {
    tail.push_back(line);
    if (tail.size() > lines) tail.pop_front();
  }
  std::string out;
  for (const std::string& l : tail) out += "  " + l + "\n";
  return out;
}

std::string Rig::all_logs() const {
  std::string out;
  for (const std::string& l : logs_) out += "--- " + l + ".log (last lines)\n" + log_tail(l);
  return out;
}

std::vector<std::string> agent_args(const SimAgent& a) {
  std::vector<std::string> args{"agent", "--name", a.name, "--out", a.out.string(), "--sim", "1", "--robot",
                                std::to_string(a.robot), "--robots", std::to_string(a.robots), "--rate",
                                fmt::format("{}", a.rate), "--start-at", fmt::format("{:.6f}", a.start_at),
                                "--interface", a.interface, "--no-ros-output"};
  if (a.keys.empty()) {
    args.insert(args.end(), {"--swarm-domain", std::to_string(a.domain)});
  } else {
    args.insert(args.end(), {"--keys", a.keys.string()});
  }
  args.insert(args.end(), a.extra.begin(), a.extra.end());
  return args;
}

double unix_in(double seconds) {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count() + seconds;
}

namespace {

net::ParticipantConfig loopback(int domain) {
  net::ParticipantConfig c;
  c.domain_id = static_cast<std::uint32_t>(domain);
  c.interface = "lo";
  return c;
}

net::SwarmLinkConfig tap_config(const std::string& partition, const std::string& name) {
  net::SwarmLinkConfig c;
  c.name = name;
  c.partition = partition;
  // The tap writes a 2 MiB message on purpose; on a loaded machine its
  // acknowledgement can hold the next write past the agents' 0.5 s.
  c.max_blocking = std::chrono::seconds(10);
  return c;
}

}  // namespace

SwarmTap::SwarmTap(int domain, const std::string& partition, const std::string& name)
    : participant(loopback(domain)), link(participant, tap_config(partition, name)) {}

bool wait_for_heartbeat(SwarmTap& tap, const std::string& robot, std::chrono::milliseconds timeout) {
  const auto until = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < until)
    for (const std::vector<std::uint8_t>& bytes : tap.link.receive(100ms)) try {
        const protocol::Message m = protocol::decode(bytes);
        if (m.header.sender == robot && std::holds_alternative<protocol::Heartbeat>(m.body)) return true;
      } catch (const protocol::ProtocolError&) {
      }
  return false;
}

std::vector<std::pair<std::string, std::vector<std::uint8_t>>> bad_messages(protocol::MessageStamper& mallory,
                                                                            const std::string& victim) {
  const auto valid = [&](protocol::Body body) { return protocol::encode(mallory.stamp(victim, std::move(body))); };
  std::vector<std::pair<std::string, std::vector<std::uint8_t>>> out;
  out.push_back({"malformed", std::vector<std::uint8_t>(100, 0xff)});  // garbage
  std::vector<std::uint8_t> cut = valid(protocol::Decline{9001, "cut short"});
  cut.resize(cut.size() / 2);
  out.push_back({"malformed", cut});  // truncated
  protocol::Chunk huge{9002, 0, 1, 2u << 20, 0, std::vector<std::uint8_t>(2u << 20, 0xab)};
  out.push_back({"malformed", valid(huge)});  // beyond the 1 MiB message limit
  std::vector<std::uint8_t> version = valid(protocol::Decline{9003, "from the future"});
  version[4] = 99;  // u16 protocol version after the magic
  out.push_back({"malformed", version});
  protocol::Offer nan_offer;
  nan_offer.encounter = 9004;
  nan_offer.pose = {std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0};
  out.push_back({"malformed", valid(nan_offer)});  // non-finite pose (checksum fine)
  std::vector<std::uint8_t> flipped = valid(protocol::Decline{9005, "bit flip"});
  flipped[flipped.size() / 2] ^= 0x10;
  out.push_back({"malformed", flipped});  // checksum mismatch
  out.push_back({"misdirected", protocol::encode(mallory.stamp("someone_else", protocol::Decline{9006, "not yours"}))});
  const std::vector<std::uint8_t> once = valid(protocol::Decline{9007, "once"});
  out.push_back({"", once});  // accepted (a decline of no open encounter: ignored)
  out.push_back({"replayed", once});
  out.push_back({"replayed", once});
  return out;
}

nlohmann::json read_json(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  return nlohmann::json::parse(in);
}

std::vector<std::string> known_origins(const nlohmann::json& stats) {
  std::vector<std::string> out;
  for (const nlohmann::json& l : stats.at("knows")) out.push_back(l.at("origin").get<std::string>());
  return out;
}

std::map<std::uint64_t, nlohmann::json> outcomes_by_id(const fs::path& encounters_json) {
  std::map<std::uint64_t, nlohmann::json> out;
  const nlohmann::json all = read_json(encounters_json);
  for (const nlohmann::json& o : all.at("encounters"))
    if (!out.emplace(o.at("encounter").get<std::uint64_t>(), o).second)
      ADD_FAILURE() << encounters_json.string() << ": encounter " << o.at("encounter") << " ended twice";
  return out;
}

bool holds(const nlohmann::json& stats, const std::string& origin) {
  const std::vector<std::string> o = known_origins(stats);
  return std::find(o.begin(), o.end(), origin) != o.end();
}

std::size_t accepted_by_both(const fs::path& a, const fs::path& b) {
  const auto oa = outcomes_by_id(a / "encounters.json"), ob = outcomes_by_id(b / "encounters.json");
  std::size_t both = 0;
  for (const auto& [id, o] : oa)
    if (o.at("end") == "accepted" && ob.count(id) && ob.at(id).at("end") == "accepted") ++both;
  return both;
}

bool wait_until(const std::function<bool()>& done, std::chrono::milliseconds timeout) {
  const auto until = std::chrono::steady_clock::now() + timeout;
  while (!done()) {
    if (std::chrono::steady_clock::now() >= until) return false;
    std::this_thread::sleep_for(50ms);
  }
  return true;
}

void expect_complete_outputs(const fs::path& dir, std::size_t scans) {
  for (const char* f : {"trajectory.tum", "map.yaml", "map.pgm", "merged_map.yaml", "merged_map.pgm", "encounters.json",
                        "stats.json", "checkpoint.dsmap", "checkpoint.json"})
    EXPECT_TRUE(fs::exists(dir / f)) << (dir / f).string() << " missing";
  const Trajectory t = read_tum(dir / "trajectory.tum");
  for (std::size_t i = 1; i < t.size(); ++i)
    ASSERT_GT(t[i].timestamp, t[i - 1].timestamp) << dir.string() << ": pose " << i << " out of order";
  EXPECT_NO_THROW(read_json(dir / "encounters.json"));
  const nlohmann::json stats = read_json(dir / "stats.json");
  // A pose per scan processed; each scan of the run processed or counted as skipped.
  EXPECT_EQ(t.size(), stats.at("scans_processed").get<std::size_t>()) << dir.string();
  EXPECT_EQ(stats.at("scans_received").get<std::size_t>(), scans) << dir.string();
  EXPECT_EQ(stats.at("scans_processed").get<std::size_t>() + stats.at("scans_skipped").get<std::size_t>(), scans)
      << dir.string();
}

}  // namespace dsswarm::mp
