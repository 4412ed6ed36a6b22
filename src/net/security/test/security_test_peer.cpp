// security_test_peer: one Cyclone DDS participant (secured with a robot's keys,
// or not) for the DDS Security tests and measurements. It publishes Blob
// samples on a topic and reports what happens on stdout, one line per event
// (ms = milliseconds since the process started):
//   ready <ms>                          participant, reader and writer exist
//   create-failed <rc>                  the participant was refused (exit 3)
//   matched <n> <ms>                    the writer's matched-reader count changed
//   first <origin> <incarnation> <ms>   first sample from a sender's incarnation
//   done <samples> <bytes> <first_ms> <last_ms>   --expect samples received
//   recreated <ms>                      the participant was rebuilt (SIGUSR1, or the
//                                       handshake watchdog with --recover-s)
// It exits on SIGTERM/SIGINT, after --lifetime-s, or when --expect is met.
#include <CLI/CLI.hpp>
#include <dds/dds.h>

#include <csignal>
#include <cstdio>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "net/security/security_config.hpp"
#include "net/security/test/peer_participant.hpp"

namespace {

volatile std::sig_atomic_t g_stop = 0, g_recreate = 0;
void on_signal(int) { g_stop = 1; }
void on_recreate_signal(int) { g_recreate = 1; }

struct Args {
  int domain = 0;
  std::string keys, name = "peer", topic = "dsswarm/sectest";
  std::size_t size = 16;
  int period_ms = 50;
  long count = 0;   // samples to write, 0 = until stopped
  long expect = 0;  // exit after this many samples from others, 0 = never
  bool silent = false;
  bool keep_all = false;
  int wait_matched = 0;  // publish only once the writer has matched this many readers (ours included)
  double lifetime_s = 60;
  double recover_s = 0;  // >0: recreate the participant when a known peer stays unmatched this long
};

struct Receipts {
  std::set<std::pair<std::string, unsigned long long>> seen;
  long samples = 0;
  double bytes = 0, first_ms = -1, last_ms = -1;
};

void report_samples(dsswarm::sectest::PeerParticipant& peer, const Args& a, Receipts& r) {
  peer.take([&](const dsswarm_sectest_Blob& s) {
    if (a.name == s.origin) return;
    if (r.seen.emplace(s.origin, s.incarnation).second) {
      std::printf("first %s %llu %.1f\n", s.origin, static_cast<unsigned long long>(s.incarnation),
                  dsswarm::sectest::ms_since_start());
    }
    ++r.samples;
    r.bytes += static_cast<double>(s.payload._length);
    r.last_ms = dsswarm::sectest::ms_since_start();
    if (r.first_ms < 0) r.first_ms = r.last_ms;
  });
}

int run(const Args& a) {
  const std::string security = a.keys.empty() ? "" : dsswarm::security::security_config_xml(a.keys, a.name);
  std::random_device rd;
  const unsigned long long incarnation = (static_cast<unsigned long long>(rd()) << 32) | rd();
  dsswarm::sectest::PeerParticipant peer(a.domain, security, a.topic, a.keep_all, a.recover_s);
  if (!peer.ok()) {
    std::printf("create-failed %d\n", peer.create_result());
    return 3;
  }
  std::printf("ready %.1f\n", dsswarm::sectest::ms_since_start());
  std::vector<unsigned char> payload(a.size, 0x5a);
  Receipts receipts;
  uint32_t seq = 0;
  while (!g_stop && dsswarm::sectest::ms_since_start() < a.lifetime_s * 1000) {
    const bool may_write = !a.silent && (a.count == 0 || seq < a.count) && peer.matched() >= a.wait_matched;
    if (may_write) peer.write(a.name, incarnation, seq++, payload);
    if (g_recreate) {
      g_recreate = 0;
      if (!peer.recreate()) return 3;
    }
    report_samples(peer, a, receipts);
    peer.report_matches();
    if (a.expect > 0 && receipts.samples >= a.expect) {
      std::printf("done %ld %.0f %.1f %.1f\n", receipts.samples, receipts.bytes, receipts.first_ms, receipts.last_ms);
      break;
    }
    std::fflush(stdout);
    if (a.period_ms > 0 || !may_write) dds_sleepfor(DDS_MSECS(a.period_ms > 0 ? a.period_ms : 1));
  }
  std::fflush(stdout);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  dsswarm::sectest::ms_since_start();  // starts the clock
  CLI::App app{"security_test_peer: one DDS participant for the security tests"};
  Args a;
  app.add_option("--domain", a.domain)->required();
  app.add_option("--keys", a.keys, "keys directory (omit: unsecured)");
  app.add_option("--name", a.name);
  app.add_option("--topic", a.topic);
  app.add_option("--size", a.size, "payload bytes");
  app.add_option("--period-ms", a.period_ms, "0: write as fast as the writer allows");
  app.add_option("--count", a.count);
  app.add_option("--expect", a.expect);
  app.add_flag("--silent", a.silent, "do not publish");
  app.add_flag("--keep-all", a.keep_all, "KEEP_ALL history (throughput), else KEEP_LAST 8");
  app.add_option("--wait-matched", a.wait_matched, "publish once the writer matched this many readers (ours too)");
  app.add_option("--lifetime-s", a.lifetime_s)->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  app.add_option("--recover-s", a.recover_s);
  CLI11_PARSE(app, argc, argv);
  std::signal(SIGTERM, on_signal);
  std::signal(SIGINT, on_signal);
  std::signal(SIGUSR1, on_recreate_signal);  // recreate the participant (recovery experiments)
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  try {
    return run(a);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
