// security_bench: what DDS Security costs on this machine, measured with
// security_test_peer processes on loopback. Prints a table per measurement
// and, as its last line, one JSON object with every figure.
//   1. time to first sample: two peers started together, unsecured vs secured
//   2. handshake per peer: N peers started together; when each has matched all
//   3. a 1 MB sample stream under several governance protection kinds
// Usage: security_bench [--domain D] [--repeats R] [--peers N] [--samples S]
#include <CLI/CLI.hpp>
#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "common/median.hpp"
#include "net/security/keystore.hpp"
#include "net/security/test/peer_process.hpp"

namespace {

namespace fs = std::filesystem;
using dsswarm::sectest::PeerProcess;
using dsswarm::security::GovernanceOptions;
using dsswarm::security::ProtectionKind;

constexpr double kTimeoutS = 60;

struct Bench {
  int domain = 170;
  int repeats = 10;
  int peers = 8;
  int samples = 500;
  int stream_repeats = 3;
  fs::path dir;
};

// The number after `field` words in `line` ("first b 123 45.6" field 3 = 45.6).
double number_at(const std::string& line, int field) {
  std::istringstream in(line);
  std::string word;
  for (int i = 0; i < field; ++i) in >> word;
  double v = -1;
  in >> v;
  return v;
}

fs::path make_keys(const Bench& b, const std::string& name, const GovernanceOptions& g, int robots) {
  dsswarm::security::KeysInitOptions o;
  o.swarm_id = b.domain;
  o.governance = g;
  const fs::path dir = b.dir / name;
  dsswarm::security::init_keys(dir, o);
  for (int i = 0; i < robots; ++i) dsswarm::security::add_robot(dir, fmt::format("p{}", i));
  return dir;
}

std::unique_ptr<PeerProcess> peer(const Bench& b, const fs::path& keys, const std::string& name,
                                  const std::vector<std::string>& extra) {
  std::vector<std::string> args{"--domain", std::to_string(b.domain), "--name", name, "--lifetime-s", "120"};
  if (!keys.empty()) args.insert(args.end(), {"--keys", keys.string()});
  args.insert(args.end(), extra.begin(), extra.end());
  return std::make_unique<PeerProcess>(SECURITY_TEST_PEER, args, b.dir / (name + ".stderr"));
}

// Median over repeats of the ms (in p0's clock, from its start) until p0
// hears p1, both started at the same moment.
double first_sample_ms(const Bench& b, const fs::path& keys) {
  std::vector<double> ms;
  for (int r = 0; r < b.repeats; ++r) {
    auto p0 = peer(b, keys, "p0", {"--period-ms", "10"});
    auto p1 = peer(b, keys, "p1", {"--period-ms", "10"});
    if (const auto line = p0->wait_for("first p1 ", kTimeoutS)) ms.push_back(number_at(*line, 3));
  }
  return ms.empty() ? -1 : dsswarm::median_in_place(ms);
}

// N peers started together: for each, ms from its "ready" until its writer
// matched every other peer's reader (N-1 remote + its own). Median and max.
std::pair<double, double> all_matched_ms(const Bench& b, const fs::path& keys) {
  std::vector<std::unique_ptr<PeerProcess>> ps;
  for (int i = 0; i < b.peers; ++i) ps.push_back(peer(b, keys, fmt::format("p{}", i), {"--period-ms", "50"}));
  std::vector<double> ms;
  for (auto& p : ps) {
    const auto ready = p->wait_for("ready", kTimeoutS);
    const auto all = p->wait_for("matched " + std::to_string(b.peers) + " ", kTimeoutS);
    if (ready && all) ms.push_back(number_at(*all, 2) - number_at(*ready, 1));
  }
  if (ms.size() != ps.size()) return {-1, -1};
  return {dsswarm::median_in_place(ms), *std::max_element(ms.begin(), ms.end())};
}

struct Stream {
  double mb_per_s = -1, writer_cpu_s = 0, reader_cpu_s = 0;
  // CPU milliseconds (writer + reader) per MB delivered.
  double cpu_ms_per_mb(int samples) const { return 1000 * (writer_cpu_s + reader_cpu_s) / samples; }
};

// p0 writes `samples` 1 MB samples as fast as reliable KEEP_ALL allows once
// matched; p1 takes them. Throughput between p1's first and last sample.
Stream one_run(const Bench& b, const fs::path& keys) {
  constexpr std::size_t kBytes = 1'000'000;
  const std::string n = std::to_string(b.samples);
  auto reader = peer(b, keys, "p1", {"--silent", "--keep-all", "--expect", n});
  auto writer = peer(b, keys, "p0",
                     {"--keep-all", "--size", std::to_string(kBytes), "--period-ms", "0", "--count", n,
                      "--wait-matched", "2"});
  Stream s;
  if (const auto done = reader->wait_for("done ", kTimeoutS)) {
    const double seconds = (number_at(*done, 4) - number_at(*done, 3)) / 1000.0;
    s.mb_per_s = seconds > 0 ? static_cast<double>(b.samples - 1) * kBytes / 1e6 / seconds : -1;
  }
  reader->stop(5);
  writer->stop(5);
  s.writer_cpu_s = writer->cpu_seconds();
  s.reader_cpu_s = reader->cpu_seconds();
  return s;
}

// Median over the stream repeats, field by field.
Stream one_mb_stream(const Bench& b, const fs::path& keys) {
  std::vector<double> rate, writer, reader;
  for (int r = 0; r < b.stream_repeats; ++r) {
    const Stream s = one_run(b, keys);
    rate.push_back(s.mb_per_s);
    writer.push_back(s.writer_cpu_s);
    reader.push_back(s.reader_cpu_s);
  }
  return {dsswarm::median_in_place(rate), dsswarm::median_in_place(writer), dsswarm::median_in_place(reader)};
}

GovernanceOptions protection(ProtectionKind rtps, ProtectionKind metadata, ProtectionKind data) {
  GovernanceOptions g;
  g.discovery = g.liveliness = g.rtps = rtps;
  g.swarm_metadata = metadata;
  g.swarm_data = data;
  return g;
}

void measure_first_sample(const Bench& b, const fs::path& secured, nlohmann::json& out) {
  out["first_sample_ms"] = {{"unsecured", first_sample_ms(b, "")}, {"secured", first_sample_ms(b, secured)}};
  fmt::print("time to first sample (median of {}): unsecured {:.0f} ms, secured {:.0f} ms\n", b.repeats,
             out["first_sample_ms"]["unsecured"].get<double>(), out["first_sample_ms"]["secured"].get<double>());
}

void measure_handshakes(const Bench& b, const fs::path& secured, nlohmann::json& out) {
  for (const auto& [label, keys] : {std::pair<std::string, fs::path>{"unsecured", ""}, {"secured", secured}}) {
    const auto [med, max] = all_matched_ms(b, keys);
    out["all_matched_ms"][label] = {{"peers", b.peers}, {"median", med}, {"max", max}};
    fmt::print("{} peers started together, {}: each matched all others after {:.0f} ms (median), {:.0f} ms (max)\n",
               b.peers, label, med, max);
  }
}

void print_stream(const Bench& b, const std::string& label, const Stream& s, nlohmann::json& out) {
  fmt::print("  {:<48} {:6.0f} MB/s  {:5.2f} CPU ms/MB (writer {:.2f} s, reader {:.2f} s)\n", label, s.mb_per_s,
             s.cpu_ms_per_mb(b.samples), s.writer_cpu_s, s.reader_cpu_s);
  out["stream_1mb"][label] = {{"mb_per_s", s.mb_per_s},
                              {"cpu_ms_per_mb", s.cpu_ms_per_mb(b.samples)},
                              {"writer_cpu_s", s.writer_cpu_s},
                              {"reader_cpu_s", s.reader_cpu_s}};
}

void measure_streams(const Bench& b, nlohmann::json& out) {
  using PK = ProtectionKind;
  const std::vector<std::pair<std::string, GovernanceOptions>> variants{
      {"rtps ENCRYPT, metadata ENCRYPT, data ENCRYPT", protection(PK::kEncrypt, PK::kEncrypt, PK::kEncrypt)},
      {"rtps SIGN, metadata SIGN, data ENCRYPT", protection(PK::kSign, PK::kSign, PK::kEncrypt)},
      {"rtps NONE, metadata SIGN, data ENCRYPT", protection(PK::kNone, PK::kSign, PK::kEncrypt)},
      {"rtps NONE, metadata NONE, data ENCRYPT", protection(PK::kNone, PK::kNone, PK::kEncrypt)},
      {"rtps SIGN, metadata SIGN, data SIGN", protection(PK::kSign, PK::kSign, PK::kSign)},
      {"rtps NONE, metadata NONE, data SIGN", protection(PK::kNone, PK::kNone, PK::kSign)},
      {"rtps NONE, metadata NONE, data NONE", protection(PK::kNone, PK::kNone, PK::kNone)}};
  fmt::print("1 MB samples, {} per run, reliable KEEP_ALL, median of {} runs:\n", b.samples, b.stream_repeats);
  print_stream(b, "unsecured", one_mb_stream(b, ""), out);
  for (std::size_t i = 0; i < variants.size(); ++i) {
    const fs::path keys = make_keys(b, fmt::format("variant{}", i), variants[i].second, 2);
    print_stream(b, variants[i].first, one_mb_stream(b, keys), out);
  }
}

}  // namespace

int main(int argc, char** argv) {
  Bench b;
  CLI::App app{"security_bench: the cost of DDS Security on loopback"};
  app.add_option("--domain", b.domain, "DDS domain id to use")->capture_default_str();
  app.add_option("--repeats", b.repeats, "Repeats of the first-sample measurement")->capture_default_str();
  app.add_option("--peers", b.peers, "Peers started together for the handshake measurement")->capture_default_str();
  app.add_option("--samples", b.samples, "1 MB samples per stream")->capture_default_str();
  app.add_option("--stream-repeats", b.stream_repeats, "Runs per protection variant")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  b.dir = fs::temp_directory_path() / ("dsswarm_security_bench_" + std::to_string(::getpid()));
  fs::remove_all(b.dir);
  fs::create_directories(b.dir);
  nlohmann::json out;
  const fs::path secured = make_keys(b, "encrypt", {}, b.peers);
  measure_first_sample(b, secured, out);
  measure_handshakes(b, secured, out);
  measure_streams(b, out);
  fs::remove_all(b.dir);
  fmt::print("{}\n", out.dump());
  return 0;
}
