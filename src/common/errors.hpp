#pragma once
// Error types shared by every module. Bad user input must surface as one of
// these (with the file/line/field named in the message) and never as a crash.
#include <stdexcept>
#include <string>
#include <string_view>

namespace dsswarm {

// Malformed or unreadable input data (logs, relation files, maps...).
// The message names the file and, where known, the line and field.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A configuration value out of its allowed range. The message names the field.
class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws ConfigError("<section>: <message>") unless ok.
inline void require_config(std::string_view section, bool ok, const std::string& message) {
  if (!ok) throw ConfigError(std::string(section) + ": " + message);
}

}  // namespace dsswarm
