#pragma once
// The checked field reader decode() (wire.cpp) reads a message with: every
// read refuses what is unsafe to use, naming the field and who sent it.
// Private to wire.cpp.
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "common/byte_io.hpp"
#include "protocol/wire.hpp"

namespace dsswarm::protocol::wire_detail {

// Reads one message's fields with the checks that make them safe to use.
class BodyReader {
 public:
  BodyReader(ByteReader& r, const WireLimits& limits, std::string who) : r_(r), limits_(limits), who_(std::move(who)) {}

  [[noreturn]] void fail(const std::string& what) const { throw ProtocolError(who_ + ": " + what); }

  double finite(const char* field);
  double in_range(const char* field, double lo, double hi);
  // A stamp may be NaN ("now") but never infinite.
  double stamp(const char* field);
  bool flag(const char* field);
  std::uint32_t count(const char* field, std::size_t max, std::size_t min_bytes_each);
  std::string name(const char* field, bool may_be_empty);
  std::string text(const char* field, std::size_t max);
  Pose2 pose(const char* field);
  std::vector<ScanPoint> points(const char* field);
  PoseHypothesis hypothesis();
  ByteReader& raw() { return r_; }
  const WireLimits& limits() const { return limits_; }

 private:
  ByteReader& r_;
  const WireLimits& limits_;
  std::string who_;
};

}  // namespace dsswarm::protocol::wire_detail
