// ROS 2 bags' metadata.yaml (src/io/rosbag2/bag_metadata.cpp), read from a
// scratch bag folder that holds the storage files a metadata file may list.
#include "common/errors.hpp"
#include "fuzz_support.hpp"
#include "io/rosbag2/bag_metadata.hpp"
#include "rosbag2_common.hpp"

namespace dsswarm::fuzz {

void write_seeds(Seeds& seeds) {
  seeds.add("mcap.yaml", rosbag2_seed_bag(rosbag2_test::Format::McapZstd).metadata);
  seeds.add("db3.yaml", rosbag2_seed_bag(rosbag2_test::Format::Db3).metadata);
  seeds.add("two-files-zstd.yaml",
            "rosbag2_bagfile_information:\n  version: 5\n  storage_identifier: mcap\n"
            "  relative_file_paths: [bag/run_0.mcap, run_1.mcap]\n  compression_format: zstd\n"
            "  compression_mode: FILE\n");
  seeds.dictionary({"rosbag2_bagfile_information:", "version:", "storage_identifier:", "relative_file_paths:",
                    "compression_format:", "compression_mode:", "mcap", "sqlite3", "zstd", "FILE", "MESSAGE",
                    "none", "run_0.mcap", "run_1.mcap", "run_0.db3", "bag/", "- ", "[", "]", "~"});
}

}  // namespace dsswarm::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace dsswarm;
  // The folder `bag` holds run_0.mcap, run_1.mcap and run_0.db3 (empty: only their names matter here).
  static const std::filesystem::path dir = [] {
    const auto bag = fuzz::scratch_dir() / "bag";
    std::filesystem::create_directories(bag);
    for (const char* name : {"bag/run_0.mcap", "bag/run_1.mcap", "bag/run_0.db3"}) fuzz::scratch_file(name, "");
    return bag;
  }();
  fuzz::scratch_file("bag/metadata.yaml", fuzz::as_text(data, size));
  const std::string source = (dir / rosbag2::kMetadataFile).string();
  fuzz::expect_clean<InputError>(source, [&] {
    const rosbag2::BagMetadata metadata = rosbag2::read_bag_metadata(dir);
    fuzz::check(!metadata.files.empty(), "metadata without storage files was accepted");
  });
  return 0;
}
