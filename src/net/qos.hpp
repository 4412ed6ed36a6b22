#pragma once
// DDS QoS as an owned value, and the presets ROS 2 tools expect (rmw_cyclonedds
// create_readwrite_qos, rclcpp's QoS profiles, tf2_ros/qos.hpp, Nav2's map).
// A preset serves writers and readers alike; max_blocking_time only matters
// to writers (ROS 2 uses infinity; we never block forever).
#include <dds/dds.h>

#include <chrono>
#include <cstdint>
#include <string_view>

namespace dsswarm::net {

// A duration as DDS counts it (nanoseconds).
dds_duration_t to_duration(std::chrono::milliseconds d);

class Qos {
 public:
  Qos();
  ~Qos();
  Qos(const Qos& other);
  Qos& operator=(const Qos& other);
  Qos(Qos&& other) noexcept;
  Qos& operator=(Qos&& other) noexcept;

  Qos& reliable(std::chrono::milliseconds max_blocking = std::chrono::milliseconds(1000));
  Qos& best_effort();
  Qos& keep_last(std::int32_t depth);
  Qos& keep_all();
  Qos& volatile_durability();
  // Late joiners get the last `depth` samples: durability_service history =
  // KEEP_LAST(depth), as rmw_cyclonedds sets it (Cyclone serves late joiners from it).
  Qos& transient_local(std::int32_t depth);
  Qos& max_samples(std::int32_t count);  // resource limit (KEEP_ALL bounds memory with it)
  Qos& user_data(std::string_view bytes);

  const dds_qos_t* get() const { return qos_; }
  dds_qos_t* get() { return qos_; }

 private:
  dds_qos_t* qos_;
};

// rclcpp's default: reliable, volatile, KEEP_LAST(depth).
Qos ros_default(std::int32_t depth = 10);
// rclcpp's SensorDataQoS: best effort, volatile, KEEP_LAST(5). A best-effort
// reader also matches reliable writers.
Qos ros_sensor_data();
// Latched topics (Nav2's /map wants depth 1): reliable, transient local,
// KEEP_LAST(depth). Matches transient-local readers (Nav2) and volatile ones (rviz2).
Qos ros_transient_local(std::int32_t depth = 1);
// tf2_ros: /tf reliable, volatile, depth 100; /tf_static transient local,
// depth 1 for broadcasters, 100 for listeners.
Qos ros_tf();
Qos ros_tf_static(std::int32_t depth = 1);
// The swarm's packets: reliable, volatile, KEEP_ALL bounded by `max_samples`
// so a slow reader throttles its writers instead of losing packets or growing
// without bound; a writer blocks at most `max_blocking`, then try_write reports it.
Qos swarm_reliable(std::int32_t max_samples = 256,
                   std::chrono::milliseconds max_blocking = std::chrono::milliseconds(500));

}  // namespace dsswarm::net
