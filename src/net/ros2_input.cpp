#include "net/ros2_input.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <deque>
#include <map>
#include <mutex>
#include <set>
#include <vector>

#include "common/errors.hpp"
#include "io/bag_common/odometry_track.hpp"
#include "net/qos.hpp"
#include "net/ros2_types.hpp"
#include "net/ros_names.hpp"
#include "common/warning_throttle.hpp"

namespace dsswarm::net {
namespace {

using Clock = std::chrono::steady_clock;

constexpr std::size_t kMaxFrameChain = 16;  // hops from the laser frame up to the base frame
constexpr std::size_t kTakeBatch = 64;

std::chrono::milliseconds millis(double seconds) {
  return std::chrono::milliseconds(static_cast<std::int64_t>(std::llround(seconds * 1000.0)));
}

void check_config(const LiveInputConfig& c) {
  const auto non_negative = [](double v, const char* name) {
    if (!(std::isfinite(v) && v >= 0.0)) throw ConfigError(fmt::format("live input: {} {} is not >= 0", name, v));
  };
  non_negative(c.wait_for_odometry, "wait_for_odometry");
  non_negative(c.max_extrapolation, "max_extrapolation");
  non_negative(c.odometry_history, "odometry_history");
  non_negative(c.warning_interval, "warning_interval");
  if (c.queue_capacity == 0 || c.max_odometry_poses < 2) {
    throw ConfigError("live input: queue_capacity must be >= 1 and max_odometry_poses >= 2");
  }
}

std::string frame_of(const char* id) { return std::string(strip_frame_slash(id == nullptr ? "" : id)); }

}  // namespace

struct LiveScanSource::Impl {
  struct PendingScan {
    LaserScan scan;
    std::string frame;           // header.frame_id without a leading '/'
    Clock::time_point deadline;  // goes out with what is known by then
  };

  struct StaticLink {
    std::string parent;
    Pose2 parent_from_child;
  };

  explicit Impl(const LiveInputConfig& c)
      : config(c),
        scan_warnings("LaserScan samples on " + c.scan_topic, millis(c.warning_interval)),
        odometry_warnings("odometry samples", millis(c.warning_interval)),
        tf_warnings("tf transforms", millis(c.warning_interval)) {}

  // ------------------------------------------------------------ arrival (Cyclone's threads)

  void add_scan(const ros::LaserScan& msg) {
    if (std::string bad = check_scan(msg, config.limits); !bad.empty()) {
      ++stats.scans_rejected;
      scan_warnings.note(bad);
      return;
    }
    ++stats.scans_received;
    if (pending.size() >= config.queue_capacity) {
      pending.pop_front();
      ++stats.scans_dropped;
    }
    const auto deadline = Clock::now() + millis(config.wait_for_odometry);
    pending.push_back({to_laser_scan(msg), frame_of(msg.header.frame_id), deadline});
  }

  void add_odometry_message(const ros::Odometry& msg) {
    if (std::string bad = check_odometry(msg, config.limits); !bad.empty()) {
      ++stats.odometry_rejected;
      odometry_warnings.note(bad);
      return;
    }
    const std::string child = frame_of(msg.child_frame_id);
    if (!child.empty()) odometry_child = child;
    add_odometry(to_seconds(msg.header.stamp), to_pose2(msg.pose.pose));
  }

  // Kept sorted by stamp; a stamp far behind the newest means the source
  // restarted (a replayed log looping), so the old track is dropped.
  void add_odometry(double stamp, const Pose2& pose) {
    ++stats.odometry_received;
    if (!odometry.empty() && stamp < odometry.back().stamp - config.odometry_history) odometry.clear();
    const auto at = std::upper_bound(odometry.begin(), odometry.end(), stamp,
                                     [](double t, const OdometrySample& p) { return t < p.stamp; });
    odometry.insert(at, {stamp, pose});
    // Poses older than the history go, except those a waiting scan still
    // needs: a consumer that falls behind the stream (a busy machine, a log
    // played fast) must not find its scans' odometry gone.
    const double oldest_wanted = pending.empty() ? odometry.back().stamp : pending.front().scan.timestamp;
    const auto expired = [&] {
      return odometry.size() > 2 && odometry.front().stamp < odometry.back().stamp - config.odometry_history &&
             odometry[1].stamp <= oldest_wanted;
    };
    while (odometry.size() > config.max_odometry_poses || expired()) odometry.pop_front();
  }

  void add_transforms(const ros::TFMessage& msg, bool is_static) {
    if (msg.transforms._length > config.limits.max_transforms) {
      ++stats.transforms_rejected;
      tf_warnings.note(fmt::format("TFMessage with {} transforms", msg.transforms._length));
      return;
    }
    for (std::uint32_t i = 0; i < msg.transforms._length; ++i) {
      const ros::TransformStamped& t = msg.transforms._buffer[i];
      const std::string parent = frame_of(t.header.frame_id), child = frame_of(t.child_frame_id);
      const bool wanted = is_static || (parent == config.odom_frame && child == config.base_frame);
      if (!wanted) continue;  // other robots' and our own map → odom are not inputs
      if (std::string bad = check_transform(t, config.limits); !bad.empty()) {
        ++stats.transforms_rejected;
        tf_warnings.note(bad);
        continue;
      }
      if (!is_static) {
        add_odometry(to_seconds(t.header.stamp), to_pose2(t.transform));
      } else if (static_links.size() < config.max_static_frames || static_links.count(child) > 0) {
        static_links[child] = {parent, to_pose2(t.transform)};
      } else {
        ++stats.transforms_rejected;
        tf_warnings.note(fmt::format("more than {} static frames", config.max_static_frames));
      }
    }
  }

  // ------------------------------------------------------------ hand-out (consumer thread)

  // The frame odometry poses refer to: the Odometry messages' child frame if they name one.
  const std::string& base_frame() const {
    const bool from_topic = config.odometry == OdometrySource::kTopic && !odometry_child.empty();
    return from_topic ? odometry_child : config.base_frame;
  }

  // The laser pose in the base frame, composed up the static tree.
  std::optional<Pose2> laser_offset(const std::string& frame) const {
    const std::string& base = base_frame();
    Pose2 base_from_laser;
    std::string current = frame;
    for (std::size_t hop = 0; hop <= kMaxFrameChain; ++hop) {
      if (current == base) return base_from_laser;
      const auto link = static_links.find(current);
      if (link == static_links.end()) return std::nullopt;
      base_from_laser = link->second.parent_from_child * base_from_laser;
      current = link->second.parent;
    }
    return std::nullopt;  // a loop, or a chain longer than any robot's
  }

  // Odometry is known at a scan's stamp once poses on both sides of it have
  // arrived: at or after it (a live robot's odometry runs a little behind its
  // scans), and at or before it (a log played backward sends a scan's own
  // odometry while every pose held is later).
  bool ready(const PendingScan& p, Clock::time_point now) const {
    if (now >= p.deadline) return true;
    const double t = p.scan.timestamp;
    const bool odometry_known = config.odometry == OdometrySource::kNone ||
                                (!odometry.empty() && odometry.front().stamp <= t && odometry.back().stamp >= t);
    return odometry_known && laser_offset(p.frame).has_value();
  }

  LaserScan finish(PendingScan p) {
    LaserScan scan = std::move(p.scan);
    if (config.odometry != OdometrySource::kNone) {
      const OdometryTrack track(std::vector<OdometrySample>(odometry.begin(), odometry.end()));
      scan.odometry = track.at(scan.timestamp, config.max_extrapolation);
      if (!scan.odometry) ++stats.scans_without_odometry;
    }
    if (const auto offset = laser_offset(p.frame)) {
      scan.laser_offset = *offset;
    } else if (warned_frames.size() < config.max_static_frames && warned_frames.insert(p.frame).second) {
      spdlog::warn("no /tf_static transform from '{}' to laser frame '{}': using the laser at the robot origin",
                   base_frame(), p.frame);
    }
    ++stats.scans_delivered;
    return scan;
  }

  std::optional<LaserScan> next(std::chrono::milliseconds timeout) {
    std::unique_lock lock(mutex);
    const auto deadline = Clock::now() + timeout;
    while (true) {
      const auto now = Clock::now();
      auto wake_at = deadline;
      if (!pending.empty()) {
        if (ready(pending.front(), now)) {
          PendingScan p = std::move(pending.front());
          pending.pop_front();
          return finish(std::move(p));
        }
        wake_at = std::min(wake_at, pending.front().deadline);
      }
      if (woken || now >= deadline) {
        woken = false;
        return std::nullopt;
      }
      changed.wait_until(lock, wake_at);
    }
  }

  // ------------------------------------------------------------ listeners

  // Takes every sample of `reader` under the lock, then wakes the consumer.
  // Nothing may escape into Cyclone's C code.
  template <class T, class Add>
  static void take_all(void* arg, dds_entity_t reader, Add add) {
    Impl& self = *static_cast<Impl*>(arg);
    try {
      {
        const std::lock_guard lock(self.mutex);
        while (take_samples<T>(reader, kTakeBatch, [&](const T& m, const dds_sample_info_t&) { add(self, m); }) > 0) {
        }
      }
      self.changed.notify_all();
    } catch (const std::exception& e) {
      spdlog::error("live input: {}", e.what());
    }
  }
  static void on_scans(dds_entity_t reader, void* arg) {
    take_all<ros::LaserScan>(arg, reader, [](Impl& s, const ros::LaserScan& m) { s.add_scan(m); });
  }
  static void on_odometry(dds_entity_t reader, void* arg) {
    take_all<ros::Odometry>(arg, reader, [](Impl& s, const ros::Odometry& m) { s.add_odometry_message(m); });
  }
  static void on_tf(dds_entity_t reader, void* arg) {
    take_all<ros::TFMessage>(arg, reader, [](Impl& s, const ros::TFMessage& m) { s.add_transforms(m, false); });
  }
  static void on_tf_static(dds_entity_t reader, void* arg) {
    take_all<ros::TFMessage>(arg, reader, [](Impl& s, const ros::TFMessage& m) { s.add_transforms(m, true); });
  }

  LiveInputConfig config;
  mutable std::mutex mutex;
  std::condition_variable changed;
  std::deque<PendingScan> pending;
  std::deque<OdometrySample> odometry;
  std::string odometry_child;
  std::map<std::string, StaticLink> static_links;  // child frame → parent
  std::set<std::string> warned_frames;
  bool woken = false;
  LiveInputStats stats;
  WarningThrottle scan_warnings, odometry_warnings, tf_warnings;

  // Last: their listeners use everything above, and they go first.
  std::optional<Topic<ros::LaserScan>> scan_topic;
  std::optional<Topic<ros::Odometry>> odom_topic;
  std::optional<Topic<ros::TFMessage>> tf_topic, tf_static_topic;
  std::optional<Reader<ros::LaserScan>> scan_reader;
  std::optional<Reader<ros::Odometry>> odom_reader;
  std::optional<Reader<ros::TFMessage>> tf_reader, tf_static_reader;
};

namespace {

// A listener object for the duration of a reader's creation (the reader copies it).
class DataListener {
 public:
  DataListener(void* arg, dds_on_data_available_fn on_data) : listener_(dds_create_listener(arg)) {
    dds_lset_data_available(listener_, on_data);
  }
  ~DataListener() { dds_delete_listener(listener_); }
  DataListener(const DataListener&) = delete;
  DataListener& operator=(const DataListener&) = delete;
  const dds_listener_t* get() const { return listener_; }

 private:
  dds_listener_t* listener_;
};

const LiveInputConfig& checked(const LiveInputConfig& config) {
  check_config(config);
  return config;
}

}  // namespace

LiveScanSource::LiveScanSource(Participant& participant, const LiveInputConfig& config)
    : impl_(std::make_unique<Impl>(checked(config))) {
  Impl& s = *impl_;
  s.scan_topic.emplace(participant, ros_topic_name(config.ns, config.scan_topic));
  s.tf_static_topic.emplace(participant, ros_topic_name(config.ns, config.tf_static_topic));
  const Qos sensor = config.reliable ? ros_default(config.reliable_depth) : ros_sensor_data();
  s.scan_reader.emplace(*s.scan_topic, sensor, "", DataListener(&s, &Impl::on_scans).get());
  s.tf_static_reader.emplace(*s.tf_static_topic, ros_tf_static(100), "",
                             DataListener(&s, &Impl::on_tf_static).get());
  if (config.odometry == OdometrySource::kTopic) {
    s.odom_topic.emplace(participant, ros_topic_name(config.ns, config.odom_topic));
    s.odom_reader.emplace(*s.odom_topic, sensor, "", DataListener(&s, &Impl::on_odometry).get());
  } else if (config.odometry == OdometrySource::kTf) {
    s.tf_topic.emplace(participant, ros_topic_name(config.ns, config.tf_topic));
    s.tf_reader.emplace(*s.tf_topic, ros_tf(), "", DataListener(&s, &Impl::on_tf).get());
  }
}

// Impl's readers go first (declared last): deleting one waits for its listener.
LiveScanSource::~LiveScanSource() = default;

std::optional<LaserScan> LiveScanSource::next(std::chrono::milliseconds timeout) { return impl_->next(timeout); }

void LiveScanSource::wake() {
  {
    const std::lock_guard lock(impl_->mutex);
    impl_->woken = true;
  }
  impl_->changed.notify_all();
}

LiveInputStats LiveScanSource::stats() const {
  const std::lock_guard lock(impl_->mutex);
  return impl_->stats;
}

int LiveScanSource::scan_publishers() const { return impl_->scan_reader->matched(); }

}  // namespace dsswarm::net
