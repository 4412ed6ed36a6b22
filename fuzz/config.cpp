// The JSON configuration file (--config): parse_config, every section.
#include "common/errors.hpp"
#include "config/config_json.hpp"
#include "fuzz_support.hpp"

namespace dsswarm::fuzz {

void write_seeds(Seeds& seeds) {
  const nlohmann::json defaults = to_json(SwarmConfig{});  // what `dsswarm config` prints
  seeds.add("defaults.json", defaults.dump(1));
  seeds.add("some-keys.json",
            R"({"filter": {"statistic": "mean", "binning": "distance"}, "map": {"levels": 2, "resolution": 0.1},)"
            R"( "swarm": {"confirm": false}})");
  seeds.add("bad-value.json", R"({"encounter": {"agree_xy": -1}, "matcher": {"evaluatons": 10}})");
  std::vector<std::string> tokens = {"true", "false", "null", "\"mean\"", "\"median\"", "\"sector\"",
                                     "\"distance\"", "1e400", "-0", "{}", "[]"};
  for (const auto& [section, keys] : defaults.items()) {
    tokens.push_back('"' + section + '"');
    for (const auto& [key, value] : keys.items()) tokens.push_back('"' + key + '"');
  }
  seeds.dictionary(tokens);
}

}  // namespace dsswarm::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace dsswarm;
  const std::string source = "fuzz.json";
  SwarmConfig config;
  fuzz::expect_clean<ConfigError>(source, [&] { parse_config(fuzz::as_text(data, size), source, config); });
  return 0;
}
