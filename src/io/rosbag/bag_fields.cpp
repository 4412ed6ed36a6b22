#include "io/rosbag/bag_fields.hpp"

#include "common/errors.hpp"

namespace dsswarm::rosbag_raw {

std::uint32_t le32(const char* p) {
  std::uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = (v << 8) | static_cast<unsigned char>(p[i]);
  return v;
}

std::uint64_t le64(const char* p) {
  return (static_cast<std::uint64_t>(le32(p + 4)) << 32) | le32(p);
}

bool parse_fields(const char* p, std::size_t n, Fields& fields) {
  fields.clear();
  std::size_t at = 0;
  while (at < n) {
    if (n - at < 4) return false;
    const std::uint32_t len = le32(p + at);
    at += 4;
    if (len > n - at) return false;
    const std::string field(p + at, len);
    at += len;
    const std::size_t eq = field.find('=');
    if (eq == std::string::npos || eq == 0) return false;
    fields[field.substr(0, eq)] = field.substr(eq + 1);
  }
  return true;
}

std::string printable(std::string text) {
  for (char& c : text) {
    if (c < 0x20 || c > 0x7e) c = '?';
  }
  return text;
}

void damaged_record(const std::string& path, const std::string& what, std::uint64_t pos) {
  throw InputError(path + ": damaged ROS1 bag: " + what + " (record at byte " +
                   std::to_string(pos) + ")");
}

std::uint64_t fixed_size_field(const std::string& path, const Fields& fields, const char* name,
                               std::size_t size, std::uint64_t pos) {
  const auto it = fields.find(name);
  if (it == fields.end() || it->second.size() != size) {
    damaged_record(path, std::string("field '") + name + "' missing or of the wrong size", pos);
  }
  return size == 8 ? le64(it->second.data()) : le32(it->second.data());
}

}  // namespace dsswarm::rosbag_raw
