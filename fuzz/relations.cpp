// Relation files of the SLAM benchmark: read_relations on a stream.
#include <cmath>
#include <sstream>

#include "common/errors.hpp"
#include "eval/relations.hpp"
#include "fuzz_support.hpp"

namespace dsswarm::fuzz {

void write_seeds(Seeds& seeds) {
  seeds.add("keyword.relations",
            "# comment\nFLOAT 10.5 11.25 0.4 -0.1 0 0 0 -0.07\n\n"
            "976052905.167303 976052911.885496 -0.056990 -0.128430 0.000000  0.0 0.0 -1.682210\r\n");
  seeds.add("short.relations", "1 2 0 0 0 0 0 0\n1 2 0 0 0 0 0\n");
  if (const std::string excerpt = seeds.shared_text("relations/intel.relations", 400); !excerpt.empty()) {
    seeds.add("intel.relations", excerpt);
  }
  seeds.dictionary({"FLOAT ", "# ", "nan", "inf", "1e308", "-0", "\r\n"});
}

}  // namespace dsswarm::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace dsswarm;
  const std::string source = "fuzz.relations";
  std::istringstream in{std::string(fuzz::as_text(data, size))};
  fuzz::expect_clean<InputError>(source, [&] {
    const std::vector<Relation> relations = read_relations(in, source);
    fuzz::check(!relations.empty(), "a file without relations was accepted");
    for (const Relation& r : relations) {
      fuzz::check(std::isfinite(r.t1) && std::isfinite(r.t2) && std::isfinite(r.motion.x) &&
                      std::isfinite(r.motion.y) && std::isfinite(r.motion.theta),
                  "a relation read is not finite");
    }
  });
  return 0;
}
