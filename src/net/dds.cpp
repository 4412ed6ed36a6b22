#include "net/dds.hpp"

#include <fmt/format.h>

#include <thread>
#include <utility>

#include "common/errors.hpp"
#include "net/qos.hpp"

namespace dsswarm::net {
namespace {

// The RTPS port mapping (7400 + 250 * domain + ...) runs out of ports above 232.
constexpr std::uint32_t kMaxDomainId = 232;
constexpr auto kPollInterval = std::chrono::milliseconds(5);

// ---------------------------------------------------------------- domains

// Cyclone allows one domain per id and process; participants share it.
struct DomainSlot {
  dds_entity_t handle = 0;
  std::string xml;
  int users = 0;
};

std::mutex& domains_mutex() {
  static std::mutex m;
  return m;
}

std::map<std::uint32_t, DomainSlot>& domains() {
  static std::map<std::uint32_t, DomainSlot> slots;
  return slots;
}

void acquire_domain(std::uint32_t id, const std::string& xml) {
  const std::lock_guard lock(domains_mutex());
  DomainSlot& slot = domains()[id];
  if (slot.users > 0) {
    if (slot.xml != xml) {
      throw ConfigError(fmt::format("DDS domain {} is already in use in this process with another configuration", id));
    }
    ++slot.users;
    return;
  }
  const dds_entity_t handle = dds_create_domain(id, xml.c_str());
  if (handle < 0) {
    domains().erase(id);
    throw ConfigError(fmt::format(
        "cannot create DDS domain {}: {} (Cyclone's log above names the setting, e.g. an unknown network interface)",
        id, dds_strretcode(handle)));
  }
  slot = {handle, xml, 1};
}

void release_domain(std::uint32_t id) {
  const std::lock_guard lock(domains_mutex());
  const auto it = domains().find(id);
  if (it == domains().end() || --it->second.users > 0) return;
  dds_delete(it->second.handle);
  domains().erase(it);
}

// ---------------------------------------------------------------- config XML

void check_xml_text(const std::string& value, const char* field) {
  if (value.empty() || value.find_first_of("<>&\"'") != std::string::npos) {
    throw ConfigError(fmt::format("DDS {} '{}' is empty or contains XML markup characters", field, value));
  }
}

bool is_loopback(const std::string& interface) {
  return interface == "lo" || interface == "127.0.0.1" || interface == "::1";
}

// An address (IPv4 or IPv6) rather than an interface name.
bool looks_like_address(const std::string& s) {
  return s.find(':') != std::string::npos || (!s.empty() && s.front() >= '0' && s.front() <= '9');
}

}  // namespace

// ---------------------------------------------------------------- errors, entities

DdsError::DdsError(std::string_view what, dds_return_t code)
    : std::runtime_error(fmt::format("{}: {}", what, dds_strretcode(code))), code_(code) {}

dds_return_t check(dds_return_t rc, std::string_view what) {
  if (rc < 0) throw DdsError(what, rc);
  return rc;
}

Entity::Entity(Entity&& other) noexcept : handle_(std::exchange(other.handle_, 0)) {}

Entity& Entity::operator=(Entity&& other) noexcept {
  std::swap(handle_, other.handle_);
  return *this;
}

Entity::~Entity() {
  // An error here means a parent already deleted it: nothing left to do.
  if (handle_ > 0) dds_delete(handle_);
}

// ---------------------------------------------------------------- participant

std::string domain_config_xml(const ParticipantConfig& c) {
  if (c.domain_id > kMaxDomainId) {
    throw ConfigError(fmt::format("DDS domain id {} is out of range 0..{}", c.domain_id, kMaxDomainId));
  }
  if (c.max_processes < 1 || c.max_processes > 120) {
    throw ConfigError(fmt::format("DDS max_processes {} is out of range 1..120", c.max_processes));
  }
  if (c.lease < std::chrono::milliseconds(100) || c.lease > std::chrono::hours(1)) {
    throw ConfigError(fmt::format("DDS lease {} ms is out of range 100 ms..1 h", c.lease.count()));
  }
  check_xml_text(c.interface, "network interface");
  std::vector<std::string> peers = c.peers;
  if (peers.empty() && is_loopback(c.interface)) peers.push_back("127.0.0.1");

  std::string general;
  if (c.interface != "auto") {
    general += fmt::format("<Interfaces><NetworkInterface {}=\"{}\"/></Interfaces>",
                           looks_like_address(c.interface) ? "address" : "name", c.interface);
  }
  std::string peer_list;
  if (!peers.empty()) {
    general += "<AllowMulticast>false</AllowMulticast>";
    for (const auto& p : peers) {
      check_xml_text(p, "discovery peer");
      peer_list += fmt::format("<Peer address=\"{}\"/>", p);
    }
    peer_list = "<Peers>" + peer_list + "</Peers>";
  }
  // ParticipantIndex auto: one index per process, so unicast discovery knows
  // which ports to probe (as rmw_cyclonedds configures it on Jazzy).
  return fmt::format(
      "<CycloneDDS xmlns=\"https://cdds.io/config\"><Domain Id=\"any\">"
      "<General>{}</General>"
      "<Discovery><ParticipantIndex>auto</ParticipantIndex>"
      "<MaxAutoParticipantIndex>{}</MaxAutoParticipantIndex>{}"
      "<LeaseDuration>{} ms</LeaseDuration></Discovery>"
      "<Internal><MaxSampleSize>{}B</MaxSampleSize></Internal>"
      "{}</Domain></CycloneDDS>",
      general, c.max_processes - 1, peer_list, c.lease.count(), c.max_sample_bytes, c.security_xml);
}

Participant::Participant(const ParticipantConfig& config) : config_(config) {
  acquire_domain(config_.domain_id, domain_config_xml(config_));
  const dds_entity_t p = dds_create_participant(config_.domain_id, nullptr, nullptr);
  if (p < 0) {  // with DDS Security: a certificate, key or signed document Cyclone could not use
    release_domain(config_.domain_id);
    throw ConfigError(fmt::format("cannot create a DDS participant in domain {}: {} (Cyclone's log above says why)",
                                  config_.domain_id, dds_strretcode(p)));
  }
  participant_ = Entity(p);
}

Participant::~Participant() {
  publishers_.clear();
  subscribers_.clear();
  participant_ = Entity();
  release_domain(config_.domain_id);
}

namespace {

dds_entity_t scoped_entity(std::map<std::string, Entity>& cache, const std::string& partition, bool publisher,
                           dds_entity_t participant) {
  const auto it = cache.find(partition);
  if (it != cache.end()) return it->second.get();
  Qos qos;
  const char* names[] = {partition.c_str()};
  if (!partition.empty()) dds_qset_partition(qos.get(), 1, names);  // none at all, as ROS 2 sets it
  const dds_entity_t e = publisher ? dds_create_publisher(participant, qos.get(), nullptr)
                                   : dds_create_subscriber(participant, qos.get(), nullptr);
  check(e, fmt::format("create {} for partition '{}'", publisher ? "publisher" : "subscriber", partition));
  cache.emplace(partition, Entity(e));
  return e;
}

}  // namespace

dds_entity_t Participant::publisher(const std::string& partition) {
  const std::lock_guard lock(mutex_);
  return scoped_entity(publishers_, partition, true, handle());
}

dds_entity_t Participant::subscriber(const std::string& partition) {
  const std::lock_guard lock(mutex_);
  return scoped_entity(subscribers_, partition, false, handle());
}

// ---------------------------------------------------------------- writers, readers

namespace {

Qos endpoint_qos(const Qos& qos, std::string_view ros_type_hash) {
  Qos q(qos);
  // ROS 2 (Iron and later) reads the type hash from endpoint USER_DATA.
  if (!ros_type_hash.empty()) q.user_data(fmt::format("typehash={};", ros_type_hash));
  return q;
}

template <class Count>
bool poll_until(std::chrono::milliseconds timeout, Count count, int wanted) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (count() < wanted) {
    if (std::chrono::steady_clock::now() >= deadline) return false;
    std::this_thread::sleep_for(kPollInterval);
  }
  return true;
}

}  // namespace

WriterBase::WriterBase(Participant& participant, dds_entity_t topic, const std::string& topic_name, const Qos& qos,
                       const std::string& partition, std::string_view ros_type_hash)
    : topic_name_(topic_name) {
  const Qos q = endpoint_qos(qos, ros_type_hash);
  writer_ = Entity(check(dds_create_writer(participant.publisher(partition), topic, q.get(), nullptr),
                         "dds_create_writer " + topic_name_));
}

int WriterBase::matched() const {
  dds_publication_matched_status_t status;
  check(dds_get_publication_matched_status(writer_.get(), &status), "publication matched status " + topic_name_);
  return static_cast<int>(status.current_count);
}

bool WriterBase::wait_for_readers(int count, std::chrono::milliseconds timeout) const {
  return poll_until(timeout, [this] { return matched(); }, count);
}

bool WriterBase::wait_for_acks(std::chrono::milliseconds timeout) const {
  const dds_return_t rc = dds_wait_for_acks(writer_.get(), to_duration(timeout));
  if (rc == DDS_RETCODE_TIMEOUT) return false;
  check(rc, "dds_wait_for_acks " + topic_name_);
  return true;
}

bool WriterBase::write_raw(const void* sample) const {
  const dds_return_t rc = dds_write(writer_.get(), sample);
  if (rc == DDS_RETCODE_TIMEOUT) return false;
  check(rc, "dds_write " + topic_name_);
  return true;
}

ReaderBase::ReaderBase(Participant& participant, dds_entity_t topic, const std::string& topic_name, const Qos& qos,
                       const std::string& partition, std::string_view ros_type_hash, const dds_listener_t* listener)
    : topic_name_(topic_name) {
  const Qos q = endpoint_qos(qos, ros_type_hash);
  reader_ = Entity(check(dds_create_reader(participant.subscriber(partition), topic, q.get(), listener),
                         "dds_create_reader " + topic_name_));
  waitset_ = Entity(check(dds_create_waitset(participant.handle()), "dds_create_waitset"));
  const dds_entity_t condition =
      check(dds_create_readcondition(reader_.get(), DDS_ANY_STATE), "dds_create_readcondition " + topic_name_);
  check(dds_waitset_attach(waitset_.get(), condition, 0), "dds_waitset_attach " + topic_name_);
}

int ReaderBase::matched() const {
  dds_subscription_matched_status_t status;
  check(dds_get_subscription_matched_status(reader_.get(), &status), "subscription matched status " + topic_name_);
  return static_cast<int>(status.current_count);
}

bool ReaderBase::wait_for_writers(int count, std::chrono::milliseconds timeout) const {
  return poll_until(timeout, [this] { return matched(); }, count);
}

bool ReaderBase::wait(std::chrono::milliseconds timeout) const {
  return check(dds_waitset_wait(waitset_.get(), nullptr, 0, to_duration(timeout)), "dds_waitset_wait " + topic_name_) >
         0;
}

int take_loaned(dds_entity_t reader, void** samples, dds_sample_info_t* infos, std::size_t max) {
  return check(dds_take(reader, samples, infos, max, static_cast<std::uint32_t>(max)), "dds_take");
}

void return_loaned(dds_entity_t reader, void** samples, int count) noexcept {
  dds_return_loan(reader, samples, count);  // only fails for a bad handle: nothing to undo
}

}  // namespace dsswarm::net
