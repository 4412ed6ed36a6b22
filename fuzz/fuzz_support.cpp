#include "fuzz_support.hpp"

#include <unistd.h>
#include <zlib.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <system_error>

namespace dsswarm::fuzz {

namespace {

void write_bytes(const std::filesystem::path& path, std::string_view bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

}  // namespace

void Seeds::add(const std::string& name, std::string_view bytes) const {
  std::filesystem::create_directories(dir_);
  write_bytes(dir_ / name, bytes);
}

void Seeds::dictionary(const std::vector<std::string>& tokens) const {
  std::filesystem::create_directories(dictionary_.parent_path());
  std::ofstream out(dictionary_, std::ios::trunc);
  for (const std::string& token : tokens) {
    out << '"';
    for (const char c : token) {
      const auto byte = static_cast<unsigned char>(c);
      if (c == '"' || c == '\\') {
        out << '\\' << c;
      } else if (byte < 0x20 || byte >= 0x7f) {
        constexpr char kHex[] = "0123456789abcdef";
        out << "\\x" << kHex[byte >> 4] << kHex[byte & 15];
      } else {
        out << c;
      }
    }
    out << "\"\n";
  }
  if (!out) throw std::runtime_error("cannot write dictionary " + dictionary_.string());
}

std::string Seeds::shared_text(const std::string& relative, std::size_t max_bytes) const {
  const std::filesystem::path path = std::filesystem::path(DSSWARM_SHARED_DATA) / relative;
  gzFile in = gzopen(path.c_str(), "rb");  // reads plain files verbatim too
  if (in == nullptr) {
    std::fprintf(stderr, "note: %s is absent, its excerpt is not a seed\n", path.c_str());
    return "";
  }
  std::string text(max_bytes, '\0');
  const int got = gzread(in, text.data(), static_cast<unsigned>(max_bytes));
  gzclose(in);
  text.resize(got > 0 ? static_cast<std::size_t>(got) : 0);
  const std::size_t last_newline = text.rfind('\n');
  text.resize(last_newline == std::string::npos ? 0 : last_newline + 1);
  return text;
}

std::string gzip(std::string_view bytes) {
  z_stream z{};
  constexpr int kGzipWindowBits = 15 + 16;  // zlib's way of asking for a gzip header
  if (deflateInit2(&z, Z_BEST_COMPRESSION, Z_DEFLATED, kGzipWindowBits, 8, Z_DEFAULT_STRATEGY) != Z_OK) {
    throw std::runtime_error("deflateInit2 failed");
  }
  std::string out(deflateBound(&z, static_cast<uLong>(bytes.size())), '\0');
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data()));
  z.avail_in = static_cast<uInt>(bytes.size());
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = static_cast<uInt>(out.size());
  const int rc = deflate(&z, Z_FINISH);
  out.resize(z.total_out);
  deflateEnd(&z);
  if (rc != Z_STREAM_END) throw std::runtime_error("deflate failed");
  return out;
}

namespace {

// Removes the scratch folder when the fuzzer exits normally.
struct ScratchDir {
  std::filesystem::path path;
  ScratchDir() {
    const std::filesystem::path shm = "/dev/shm";  // memory: one file write per input
    std::error_code ec;
    const std::filesystem::path base =
        std::filesystem::is_directory(shm, ec) ? shm : std::filesystem::temp_directory_path();
    path = base / ("dsswarm-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(path);
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
};

}  // namespace

const std::filesystem::path& scratch_dir() {
  static const ScratchDir dir;
  return dir.path;
}

std::filesystem::path scratch_file(const std::string& name, std::string_view bytes) {
  const std::filesystem::path path = scratch_dir() / name;
  write_bytes(path, bytes);
  return path;
}

void fail(std::string_view what) {
  std::fprintf(stderr, "fuzz invariant broken: %.*s\n", static_cast<int>(what.size()), what.data());
  std::abort();
}

}  // namespace dsswarm::fuzz

// libFuzzer calls this once before fuzzing. With DSSWARM_FUZZ_WRITE_SEEDS and
// DSSWARM_FUZZ_WRITE_DICT set, the target writes its seeds and dictionary
// there instead, and exits.
extern "C" int LLVMFuzzerInitialize(int* /*argc*/, char*** /*argv*/) {
  const char* dir = std::getenv("DSSWARM_FUZZ_WRITE_SEEDS");
  const char* dictionary = std::getenv("DSSWARM_FUZZ_WRITE_DICT");
  if (dir != nullptr && dictionary != nullptr) {
    dsswarm::fuzz::Seeds seeds{dir, dictionary};
    dsswarm::fuzz::write_seeds(seeds);
    std::exit(0);
  }
  return 0;
}
