// .dsmap files and encounter messages: decode_dsmap on raw bytes (header,
// checksums, zstd frame, then the payload).
#include "common/errors.hpp"
#include "dsmap_common.hpp"
#include "fuzz_support.hpp"
#include "io/maps/dsmap.hpp"

namespace dsswarm::fuzz {

void write_seeds(Seeds& seeds) {
  for (const auto& [name, snapshot] : dsmap_seed_snapshots()) {
    const std::vector<std::uint8_t> bytes = encode_dsmap(snapshot);
    const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    seeds.add(name + ".dsmap", text);
    if (name == "one-tile") seeds.add("truncated.dsmap", text.substr(0, text.size() - 7));
  }
  // Magic and format version 1, the zstd frame magic.
  seeds.dictionary({"DSMAP", std::string("DSMAP\x01\x00", 7), "\x28\xb5\x2f\xfd"});
}

}  // namespace dsswarm::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace dsswarm;
  const std::string source = "fuzz.dsmap";
  fuzz::expect_clean<InputError>(source, [&] { fuzz::check_round_trip(decode_dsmap({data, size}, source), source); });
  return 0;
}
