// Swarm scenario files (YAML): parse_swarm_scenario, with a scratch folder
// holding the logs, config and relations a scenario may name.
#include <algorithm>
#include <cmath>

#include "apps/swarm_scenario.hpp"
#include "common/errors.hpp"
#include "fuzz_support.hpp"

namespace dsswarm::fuzz {
namespace {

// The unit tests' log (src/apps/swarm_scenario_test.cpp): twelve scans one
// second apart from t = 100, the fifth running backwards.
std::string synthetic_log() {
  const double stamps[] = {100, 101, 102, 103, 102.5, 104, 105, 106, 107, 108, 109, 110};
  std::string text = "# synthetic CARMEN log\n";
  for (int i = 0; i < 12; ++i) {
    text += "FLASER 3 1 2 3 " + std::to_string(i) + " 0 0 " + std::to_string(i) + " 0 0 " + std::to_string(stamps[i]) +
            " host 0\n";
  }
  return text;
}

const std::filesystem::path& scenario_path() {
  static const std::filesystem::path path = [] {
    scratch_file("log.txt", synthetic_log());
    scratch_file("bad.log", "FLASER 3 1 2\n");
    scratch_file("slam.json", "{}");
    scratch_file("a.relations", "100 101 1 0 0 0 0 0\n");
    return scratch_dir() / "scenario.yaml";
  }();
  return path;
}

}  // namespace

void write_seeds(Seeds& seeds) {
  seeds.add("two-robots.yaml", R"(name: split
config: slam.json
relations: a.relations
agents:
  - name: robot1
    log: log.txt
    from: 2
    to: 5
  - name: robot2
    log: log.txt
    from_fraction: 0.5
    to_fraction: 1.0
    direction: backward
    start: 0.5
encounters:
  - agents: [robot1, robot2]
    time: 1.5
  - agents: [robot2, robot1]
    log_times: [108, 103]
)");
  seeds.add("one-robot.yaml", "agents:\n  - {name: solo, log: log.txt, direction: forward}\n");
  seeds.add("bad-log.yaml", "agents:\n  - name: r\n    log: bad.log\nencounters: ~\n");
  seeds.dictionary({"name:", "config:", "relations:", "agents:", "encounters:", "log:", "from:", "from_fraction:",
                    "to:", "to_fraction:", "direction:", "start:", "time:", "log_times:", "forward", "backward",
                    "log.txt", "bad.log", "slam.json", "a.relations", "- ", "[", "]", "{", "}", ": ", "~", "&a",
                    "*a", "!!str", ".inf", ".nan", "1e400"});
}

}  // namespace dsswarm::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace dsswarm;
  const std::filesystem::path& path = fuzz::scenario_path();
  fuzz::expect_clean<InputError>(path.string(), [&] {
    const SwarmScenario s = parse_swarm_scenario(std::string(fuzz::as_text(data, size)), path);
    fuzz::check(!s.streams.empty(), "a scenario without agents was accepted");
    for (const AgentStream& stream : s.streams) {
      fuzz::check(!stream.scans.empty() && stream.clock.size() == stream.scans.size() &&
                      std::is_sorted(stream.clock.begin(), stream.clock.end()),
                  "an agent's scans or clock are broken");
    }
    for (const EncounterEvent& e : s.events) {
      fuzz::check(e.a < s.streams.size() && e.b < s.streams.size() && e.a != e.b && std::isfinite(e.time),
                  "an encounter is broken");
    }
  });
  return 0;
}
