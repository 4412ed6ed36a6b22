// Whole CARMEN files, plain or gzip (decided by the first bytes): read_log on
// the input written to a file, through TextLineReader's decompression.
#include "carmen_common.hpp"
#include "common/errors.hpp"
#include "fuzz_support.hpp"
#include "io/logs/log_reader.hpp"

namespace dsswarm::fuzz {

void write_seeds(Seeds& seeds) {
  for (const auto& [name, text] : carmen_seed_logs(seeds)) {
    seeds.add(name + ".log", text);
    seeds.add(name + ".log.gz", gzip(text));
  }
  const std::string small = gzip("FLASER 3 1 2 3 0 0 0 0 0 0 1.0 host 0\nFLASER 3 1 2 3 0 0 0 0 0 0 2.0 host 0\n");
  seeds.add("truncated.log.gz", small.substr(0, small.size() / 2));
  seeds.add("no-trailer.log.gz", small.substr(0, small.size() - 8));
  seeds.add("empty.log.gz", gzip(""));
  std::vector<std::string> tokens = carmen_dictionary();
  tokens.push_back("\x1f\x8b\x08");  // gzip magic and deflate
  seeds.dictionary(tokens);
}

}  // namespace dsswarm::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace dsswarm;
  const auto path = fuzz::scratch_file("input.log", fuzz::as_text(data, size));
  fuzz::expect_clean<InputError>(path.string(), [&] { fuzz::check_log(read_log(path)); });
  return 0;
}
