#pragma once
// Shared by the libFuzzer targets of this folder (one file per parser).
//
// A target defines
//   extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);
//   void dsswarm::fuzz::write_seeds(Seeds& seeds);  // its seed corpus
// and calls its parser through expect_clean(): the error bad input must give
// passes (if its message names the source), anything else escapes and
// libFuzzer reports it, like a crash, hang, leak or sanitizer finding.
// `scripts/fuzz.sh --make-corpus` runs each target with
// DSSWARM_FUZZ_WRITE_SEEDS=fuzz/corpus/NAME and
// DSSWARM_FUZZ_WRITE_DICT=fuzz/dict/NAME.dict to regenerate both.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace dsswarm::fuzz {

// Writes one target's seed files (into its corpus folder) and its libFuzzer
// dictionary (tokens the mutator should insert: keywords, keys, magic bytes).
class Seeds {
 public:
  Seeds(std::filesystem::path dir, std::filesystem::path dictionary)
      : dir_(std::move(dir)), dictionary_(std::move(dictionary)) {}
  void add(const std::string& name, std::string_view bytes) const;
  void dictionary(const std::vector<std::string>& tokens) const;
  // The start of a file under the shared data folder (gunzipped if it is
  // gzip), cut after the last whole line within `max_bytes`; empty (with a
  // note on stderr) if the data is absent.
  std::string shared_text(const std::string& relative, std::size_t max_bytes) const;

 private:
  std::filesystem::path dir_;
  std::filesystem::path dictionary_;
};

void write_seeds(Seeds& seeds);  // defined by each target

std::string gzip(std::string_view bytes);

inline std::string_view as_text(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

// For parsers that only read files: writes `bytes` to a file `name` in a
// scratch folder of this process (removed at exit) and returns its path.
std::filesystem::path scratch_file(const std::string& name, std::string_view bytes);
const std::filesystem::path& scratch_dir();

// Keeps a value computed from bytes a parser handed over, so that reading
// them (where ASan checks their bounds) is not optimised away.
inline void keep(std::size_t value) {
  static volatile std::size_t sink = 0;
  sink = sink + value;
}

// Reports a broken invariant and aborts (libFuzzer saves the input).
[[noreturn]] void fail(std::string_view what);
inline void check(bool ok, std::string_view what) {
  if (!ok) fail(what);
}

// Runs `parse`; an `Error` is the expected outcome of bad input, and its
// message must name `source` (the file, as users see it).
template <typename Error, typename Parse>
void expect_clean(const std::string& source, Parse&& parse) {
  try {
    parse();
  } catch (const Error& e) {
    const std::string_view message = e.what();
    if (message.find(source) == std::string_view::npos) {
      fail(std::string("error message does not name ") + source + ": " + std::string(message));
    }
  }
}

}  // namespace dsswarm::fuzz
