// Figures of the DDS layer on this machine, between two processes on
// loopback: discovery + first sample, LaserScan round trip, and the time to
// write (and have delivered) big OccupancyGrids.
//   build/bench/net_bench [DOMAIN]
#include <fmt/core.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "net/dds.hpp"
#include "net/qos.hpp"
#include "net/ros2_output.hpp"
#include "net/ros2_types.hpp"
#include "net/sensor_publisher.hpp"

namespace {

using namespace dsswarm;
using namespace dsswarm::net;
using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

constexpr int kRoundTrips = 2000;
constexpr int kBeams = 720;

double ms(Clock::duration d) { return std::chrono::duration<double, std::milli>(d).count(); }

ParticipantConfig config(std::uint32_t domain) {
  ParticipantConfig c;
  c.domain_id = domain;
  c.interface = "lo";
  return c;
}

LaserScan bench_scan(double stamp) {
  LaserScan s;
  s.timestamp = stamp;
  s.angle_min = -3.14;
  s.angle_increment = 6.28 / kBeams;
  s.range_max = 30.0;
  s.ranges.assign(kBeams, 5.0f);
  return s;
}

// The other process: sends every scan back, and a scan stamped like each map it gets.
[[noreturn]] void echo(std::uint32_t domain) {
  {
    Participant p(config(domain));
    Topic<ros::LaserScan> ping_topic(p, "rt/bench/ping"), pong_topic(p, "rt/bench/pong");
    Topic<ros::OccupancyGrid> map_topic(p, "rt/bench/map");
    Reader<ros::LaserScan> ping(ping_topic, ros_default(100));
    Reader<ros::OccupancyGrid> maps(map_topic, ros_transient_local(1));
    Writer<ros::LaserScan> pong(pong_topic, ros_default(100));
    const std::string frame = "laser";
    bool quit = false;
    while (!quit && getppid() != 1) {
      ping.wait(1ms);  // polls the maps too: at most 1 ms late
      ping.take(64, [&](const ros::LaserScan& m, const dds_sample_info_t&) {
        quit = std::string(m.header.frame_id) == "quit";
        pong.write(m);
      });
      maps.take(4, [&](const ros::OccupancyGrid& m, const dds_sample_info_t&) {
        LaserScan ack = bench_scan(to_seconds(m.header.stamp));
        pong.write(to_ros_scan(ack, frame));
      });
    }
  }
  std::_Exit(0);
}

// Waits for the pong stamped `stamp`; returns when it came.
std::optional<Clock::time_point> wait_pong(const Reader<ros::LaserScan>& pong, double stamp,
                                           std::chrono::milliseconds timeout) {
  const auto deadline = Clock::now() + timeout;
  while (Clock::now() < deadline) {
    pong.wait(1ms);
    bool got = false;
    pong.take(64, [&](const ros::LaserScan& m, const dds_sample_info_t&) {
      got = got || to_seconds(m.header.stamp) == stamp;
    });
    if (got) return Clock::now();
  }
  return std::nullopt;
}

void round_trips(const Writer<ros::LaserScan>& ping, const Reader<ros::LaserScan>& pong) {
  std::vector<double> rtt;
  const std::string frame = "laser";
  for (int i = 0; i < kRoundTrips; ++i) {
    const LaserScan s = bench_scan(1000.0 + i);
    const auto t0 = Clock::now();
    ping.write(to_ros_scan(s, frame));
    const auto t1 = wait_pong(pong, s.timestamp, 1s);
    if (t1) rtt.push_back(ms(*t1 - t0));
  }
  std::sort(rtt.begin(), rtt.end());
  if (rtt.empty()) return;
  fmt::print("LaserScan ({} beams, {} B) round trip: median {:.3f} ms, p99 {:.3f} ms, max {:.3f} ms ({} of {})\n",
             kBeams, kBeams * 4 + 60, rtt[rtt.size() / 2], rtt[rtt.size() * 99 / 100], rtt.back(), rtt.size(),
             kRoundTrips);
}

void maps(Participant& p, const Reader<ros::LaserScan>& pong, int side) {
  Topic<ros::OccupancyGrid> topic(p, "rt/bench/map");
  Writer<ros::OccupancyGrid> writer(topic, ros_transient_local(1).reliable(10s));
  writer.wait_for_readers(1, 5s);
  GridRaster raster;
  raster.width = raster.height = side;
  raster.cells.assign(static_cast<std::size_t>(side) * side, DsMass{0.7f, 0.1f});
  std::vector<double> write_ms, delivered_ms;
  for (int i = 0; i < 5; ++i) {
    const double stamp = 5000.0 + side + i;
    const auto t0 = Clock::now();
    std::vector<std::int8_t> cells(raster.cells.size());
    for (std::size_t c = 0; c < cells.size(); ++c) cells[c] = occupancy_grid_value(raster.cells[c], {});
    writer.write(to_occupancy_grid(raster, cells, stamp, "map"));
    write_ms.push_back(ms(Clock::now() - t0));
    const auto t1 = wait_pong(pong, stamp, 10s);
    if (t1) delivered_ms.push_back(ms(*t1 - t0));
  }
  std::sort(write_ms.begin(), write_ms.end());
  std::sort(delivered_ms.begin(), delivered_ms.end());
  fmt::print("OccupancyGrid {}x{} ({:.1f} MB): convert + dds_write median {:.1f} ms, "
             "delivered median {:.1f} ms ({} of 5)\n",
             side, side, side * side / 1e6, write_ms[write_ms.size() / 2],
             delivered_ms.empty() ? 0.0 : delivered_ms[delivered_ms.size() / 2], delivered_ms.size());
}

}  // namespace

int main(int argc, char** argv) {
  const std::uint32_t domain = argc > 1 ? static_cast<std::uint32_t>(std::atoi(argv[1])) : 77;
  const pid_t child = fork();
  if (child == 0) echo(domain);
  std::this_thread::sleep_for(500ms);  // the echo process is up and discovered nothing yet
  {
    const auto t0 = Clock::now();
    Participant p(config(domain));
    Topic<ros::LaserScan> ping_topic(p, "rt/bench/ping"), pong_topic(p, "rt/bench/pong");
    Writer<ros::LaserScan> ping(ping_topic, ros_default(100));
    Reader<ros::LaserScan> pong(pong_topic, ros_default(100));
    // Write until the first echo: discovery both ways plus one round trip.
    const std::string frame = "laser";
    std::optional<Clock::time_point> first, matched;
    for (int i = 0; i < 5000 && !first; ++i) {
      if (!matched && ping.matched() > 0 && pong.matched() > 0) matched = Clock::now();
      const LaserScan s = bench_scan(1.0 + i);
      ping.write(to_ros_scan(s, frame));
      first = wait_pong(pong, s.timestamp, 1ms);
    }
    if (first && matched) {
      fmt::print("participant created -> endpoints matched both ways {:.1f} ms -> first sample echoed {:.1f} ms\n",
                 ms(*matched - t0), ms(*first - t0));
    }
    round_trips(ping, pong);
    maps(p, pong, 1000);
    maps(p, pong, 2000);
    LaserScan quit = bench_scan(0.0);
    const std::string quit_frame = "quit";
    ping.write(to_ros_scan(quit, quit_frame));
    ping.wait_for_acks(2s);
  }
  int status = 0;
  waitpid(child, &status, 0);
  return 0;
}
