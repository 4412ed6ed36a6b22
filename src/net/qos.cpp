#include "net/qos.hpp"

#include <new>
#include <utility>

namespace dsswarm::net {
dds_duration_t to_duration(std::chrono::milliseconds d) {
  return DDS_MSECS(static_cast<dds_duration_t>(d.count()));
}

namespace {

dds_qos_t* new_qos() {
  dds_qos_t* qos = dds_create_qos();
  if (qos == nullptr) throw std::bad_alloc();
  return qos;
}

}  // namespace

Qos::Qos() : qos_(new_qos()) {}

Qos::~Qos() {
  if (qos_ != nullptr) dds_delete_qos(qos_);
}

Qos::Qos(const Qos& other) : qos_(new_qos()) { dds_copy_qos(qos_, other.qos_); }

Qos& Qos::operator=(const Qos& other) {
  if (this != &other) {
    Qos copy(other);
    std::swap(qos_, copy.qos_);
  }
  return *this;
}

Qos::Qos(Qos&& other) noexcept : qos_(std::exchange(other.qos_, nullptr)) {}

Qos& Qos::operator=(Qos&& other) noexcept {
  std::swap(qos_, other.qos_);
  return *this;
}

Qos& Qos::reliable(std::chrono::milliseconds max_blocking) {
  dds_qset_reliability(qos_, DDS_RELIABILITY_RELIABLE, to_duration(max_blocking));
  return *this;
}

Qos& Qos::best_effort() {
  dds_qset_reliability(qos_, DDS_RELIABILITY_BEST_EFFORT, 0);
  return *this;
}

Qos& Qos::keep_last(std::int32_t depth) {
  dds_qset_history(qos_, DDS_HISTORY_KEEP_LAST, depth);
  return *this;
}

Qos& Qos::keep_all() {
  dds_qset_history(qos_, DDS_HISTORY_KEEP_ALL, DDS_LENGTH_UNLIMITED);
  return *this;
}

Qos& Qos::volatile_durability() {
  dds_qset_durability(qos_, DDS_DURABILITY_VOLATILE);
  return *this;
}

Qos& Qos::transient_local(std::int32_t depth) {
  dds_qset_durability(qos_, DDS_DURABILITY_TRANSIENT_LOCAL);
  dds_qset_durability_service(qos_, 0, DDS_HISTORY_KEEP_LAST, depth, DDS_LENGTH_UNLIMITED, DDS_LENGTH_UNLIMITED,
                              DDS_LENGTH_UNLIMITED);
  return keep_last(depth);
}

Qos& Qos::max_samples(std::int32_t count) {
  dds_qset_resource_limits(qos_, count, DDS_LENGTH_UNLIMITED, DDS_LENGTH_UNLIMITED);
  return *this;
}

Qos& Qos::user_data(std::string_view bytes) {
  dds_qset_userdata(qos_, bytes.data(), bytes.size());
  return *this;
}

Qos ros_default(std::int32_t depth) {
  Qos qos;
  qos.reliable().volatile_durability().keep_last(depth);
  return qos;
}

Qos ros_sensor_data() {
  Qos qos;
  qos.best_effort().volatile_durability().keep_last(5);
  return qos;
}

Qos ros_transient_local(std::int32_t depth) {
  Qos qos;
  qos.reliable().transient_local(depth);
  return qos;
}

Qos ros_tf() { return ros_default(100); }

Qos ros_tf_static(std::int32_t depth) { return ros_transient_local(depth); }

Qos swarm_reliable(std::int32_t max_samples, std::chrono::milliseconds max_blocking) {
  Qos qos;
  qos.reliable(max_blocking).volatile_durability().keep_all().max_samples(max_samples);
  return qos;
}

}  // namespace dsswarm::net
