#pragma once
// A thin RAII layer over Cyclone DDS's C API (Debian ships no C++ binding):
// a participant in a domain we configure ourselves, and typed topics,
// writers and readers over idlc-generated C structs. Every entity is deleted
// by its owner's destructor — a reader that vanishes without dds_delete makes
// its writers' dds_wait_for_acks block for a lease duration.
//
// Lifetimes: a Participant must outlive its topics, readers and writers.
// Failed calls throw DdsError carrying Cyclone's reason (dds_strretcode).
#include <dds/dds.h>

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "net/qos.hpp"

namespace dsswarm::net {

class DdsError : public std::runtime_error {
 public:
  DdsError(std::string_view what, dds_return_t code);
  dds_return_t code() const { return code_; }

 private:
  dds_return_t code_;
};

// Returns `rc`, or throws DdsError("what: <Cyclone's reason>") when it is negative.
dds_return_t check(dds_return_t rc, std::string_view what);

// An owned entity handle (deleting an entity deletes its children too).
class Entity {
 public:
  Entity() = default;
  explicit Entity(dds_entity_t handle) : handle_(handle) {}
  Entity(Entity&& other) noexcept;
  Entity& operator=(Entity&& other) noexcept;
  Entity(const Entity&) = delete;
  Entity& operator=(const Entity&) = delete;
  ~Entity();

  dds_entity_t get() const { return handle_; }

 private:
  dds_entity_t handle_ = 0;
};

struct ParticipantConfig {
  std::uint32_t domain_id = 0;  // 0..232 (the RTPS port mapping allows no more)
  // Network interface name or address; "auto" lets Cyclone choose. "lo"
  // (loopback, no multicast here) selects unicast discovery on 127.0.0.1.
  std::string interface = "auto";
  // Unicast discovery peers (addresses or host names); empty = multicast
  // discovery, except on loopback. With peers, multicast is off.
  std::vector<std::string> peers;
  // Processes per machine in this domain (Discovery/MaxAutoParticipantIndex + 1):
  // unicast discovery only reaches participant indices below it.
  int max_processes = 32;
  // Larger samples are dropped by Cyclone, sent or received (Internal/MaxSampleSize):
  // a peer cannot make us allocate more. Fits a 4000x4000 /map.
  std::uint32_t max_sample_bytes = 32u << 20;
  // A complete <Security>...</Security> element (DDS Security plugins), or empty.
  std::string security_xml;
  // How long peers keep this participant after its last sign of life
  // (Discovery/LeaseDuration; Cyclone's default 10 s). A process killed
  // without a goodbye stays matched that long, and reliable writers to it
  // stall: messages to its restarted successor wait behind them.
  std::chrono::milliseconds lease{10000};
};

// The Cyclone configuration of a domain as dds_create_domain takes it.
// Throws ConfigError for values that cannot go into it (domain id, characters).
std::string domain_config_xml(const ParticipantConfig& config);

class Participant {
 public:
  // Creates (or, within this process, shares) the domain with the
  // configuration above, then a participant in it. Participants of one domain
  // in one process must agree on the configuration. A configuration Cyclone
  // refuses (unknown interface, unusable security files) is a ConfigError.
  explicit Participant(const ParticipantConfig& config);
  ~Participant();
  Participant(const Participant&) = delete;
  Participant& operator=(const Participant&) = delete;

  dds_entity_t handle() const { return participant_.get(); }
  const ParticipantConfig& config() const { return config_; }

  // The publisher / subscriber for `partition` ("" = the default partition,
  // where ROS 2 lives; a swarm id keeps swarms apart), made on first use.
  dds_entity_t publisher(const std::string& partition);
  dds_entity_t subscriber(const std::string& partition);

 private:
  ParticipantConfig config_;
  Entity participant_;
  std::mutex mutex_;
  std::map<std::string, Entity> publishers_;
  std::map<std::string, Entity> subscribers_;
};

// The type behind a topic: specialised for every idlc-generated type we use
// (ros2_types.hpp, swarm_types.hpp) with
//   static const dds_topic_descriptor_t& descriptor();
//   static constexpr std::string_view ros_type_hash;  // "RIHS01_…", or "" for non-ROS types
template <class T>
struct TopicType;

template <class T>
class Topic {
 public:
  Topic(Participant& participant, const std::string& name)
      : participant_(&participant),
        name_(name),
        topic_(check(dds_create_topic(participant.handle(), &TopicType<T>::descriptor(), name.c_str(), nullptr,
                                      nullptr),
                     "dds_create_topic " + name)) {}

  Participant& participant() const { return *participant_; }
  const std::string& name() const { return name_; }
  dds_entity_t handle() const { return topic_.get(); }

 private:
  Participant* participant_;
  std::string name_;
  Entity topic_;
};

// Untyped halves, so the templates below stay one-liners.
class WriterBase {
 public:
  // `ros_type_hash` non-empty: USER_DATA "typehash=<hash>;" as ROS 2 endpoints carry it.
  WriterBase(Participant& participant, dds_entity_t topic, const std::string& topic_name, const Qos& qos,
             const std::string& partition, std::string_view ros_type_hash);

  int matched() const;  // readers currently matched
  bool wait_for_readers(int count, std::chrono::milliseconds timeout) const;
  // All written samples acknowledged by all reliable readers within `timeout`.
  bool wait_for_acks(std::chrono::milliseconds timeout) const;
  dds_entity_t handle() const { return writer_.get(); }

 protected:
  // False when the write blocked longer than the QoS max_blocking_time (the
  // sample was not sent); other failures throw.
  bool write_raw(const void* sample) const;

 private:
  std::string topic_name_;
  Entity writer_;
};

template <class T>
class Writer : public WriterBase {
 public:
  Writer(const Topic<T>& topic, const Qos& qos, const std::string& partition = "")
      : WriterBase(topic.participant(), topic.handle(), topic.name(), qos, partition, TopicType<T>::ros_type_hash) {}

  bool try_write(const T& sample) const { return write_raw(&sample); }
  // Like try_write, but a timeout throws too.
  void write(const T& sample) const {
    if (!write_raw(&sample)) throw DdsError("dds_write timed out", DDS_RETCODE_TIMEOUT);
  }
};

// Taking samples on loan from a reader handle (listener callbacks get the
// handle, not our Reader): take_loaned returns the count, samples[i] valid
// until return_loaned.
inline constexpr std::size_t kMaxTakeBatch = 32;
int take_loaned(dds_entity_t reader, void** samples, dds_sample_info_t* infos, std::size_t max);
void return_loaned(dds_entity_t reader, void** samples, int count) noexcept;

// Takes up to `max` samples of type T from `reader` (kMaxTakeBatch at a time)
// and calls on_sample(const T&, const dds_sample_info_t&) for each one that
// carries data; the sample is valid during the call only. Returns that count.
template <class T, class OnSample>
std::size_t take_samples(dds_entity_t reader, std::size_t max, OnSample&& on_sample) {
  struct LoanGuard {
    dds_entity_t reader;
    void** samples;
    int count;
    ~LoanGuard() { return_loaned(reader, samples, count); }
  };
  std::size_t handed = 0;
  while (max > 0) {
    void* samples[kMaxTakeBatch] = {};
    dds_sample_info_t infos[kMaxTakeBatch];
    const int n = take_loaned(reader, samples, infos, max < kMaxTakeBatch ? max : kMaxTakeBatch);
    if (n <= 0) break;
    const LoanGuard guard{reader, samples, n};
    for (int i = 0; i < n; ++i) {
      if (!infos[i].valid_data) continue;
      on_sample(*static_cast<const T*>(samples[i]), infos[i]);
      ++handed;
    }
    max -= static_cast<std::size_t>(n);
  }
  return handed;
}

class ReaderBase {
 public:
  ReaderBase(Participant& participant, dds_entity_t topic, const std::string& topic_name, const Qos& qos,
             const std::string& partition, std::string_view ros_type_hash, const dds_listener_t* listener);

  int matched() const;  // writers currently matched
  bool wait_for_writers(int count, std::chrono::milliseconds timeout) const;
  // Blocks until a sample is available or `timeout` passes.
  bool wait(std::chrono::milliseconds timeout) const;
  dds_entity_t handle() const { return reader_.get(); }

 private:
  std::string topic_name_;
  Entity reader_;
  Entity waitset_;  // holds the read condition
};

template <class T>
class Reader : public ReaderBase {
 public:
  // `listener` (optional) is copied; its callbacks run on Cyclone's threads.
  Reader(const Topic<T>& topic, const Qos& qos, const std::string& partition = "",
         const dds_listener_t* listener = nullptr)
      : ReaderBase(topic.participant(), topic.handle(), topic.name(), qos, partition, TopicType<T>::ros_type_hash,
                   listener) {}

  // See take_samples.
  template <class OnSample>
  std::size_t take(std::size_t max, OnSample&& on_sample) const {
    return take_samples<T>(handle(), max, std::forward<OnSample>(on_sample));
  }
};

}  // namespace dsswarm::net
