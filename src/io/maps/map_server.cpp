#include "io/maps/map_server.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

#include "common/errors.hpp"
#include "io/atomic_file.hpp"
#include "io/maps/pgm.hpp"

namespace dsswarm {
namespace {

namespace fs = std::filesystem;

// ---------------------------------------------------------------- writing

// map_saver's pixel values (before negate).
constexpr int kOccupiedPixel = 0;
constexpr int kFreePixel = 254;
constexpr int kUnknownPixel = 205;

// What map_server computes from a (non-negated) pixel value.
double pixel_occupancy(int value) { return (255.0 - value) / 255.0; }

// map_saver's 205 reads back as unknown for its default thresholds; for other
// thresholds pick a grey that lands between them, so the round trip holds.
int unknown_pixel_for(const MapServerOptions& o) {
  const auto is_unknown = [&](int v) {
    const double p = pixel_occupancy(v);
    return !(p > o.occupied_thresh) && !(p < o.free_thresh);
  };
  if (is_unknown(kUnknownPixel)) return kUnknownPixel;
  const double middle = 0.5 * (o.free_thresh + o.occupied_thresh);
  const int v = static_cast<int>(std::lround(255.0 * (1.0 - middle)));
  if (v >= 0 && v <= 255 && is_unknown(v)) return v;
  throw ConfigError(fmt::format(
      "map_server thresholds: free_thresh {} and occupied_thresh {} are too close for any grey level "
      "to mean unknown",
      o.free_thresh, o.occupied_thresh));
}

void check_raster(const GridRaster& raster, const fs::path& yaml_path) {
  const auto fail = [&](const std::string& what) {
    throw InputError(fmt::format("cannot write map {}: {}", yaml_path.string(), what));
  };
  if (raster.width <= 0 || raster.height <= 0) fail(fmt::format("raster is empty ({}x{})", raster.width, raster.height));
  if (raster.width > kMaxPgmSide || raster.height > kMaxPgmSide) {
    fail(fmt::format("raster {}x{} is larger than {} cells a side", raster.width, raster.height, kMaxPgmSide));
  }
  if (raster.cells.size() != static_cast<std::size_t>(raster.width) * static_cast<std::size_t>(raster.height)) {
    fail(fmt::format("raster has {} cells, expected {}x{}", raster.cells.size(), raster.width, raster.height));
  }
  if (!std::isfinite(raster.resolution) || raster.resolution <= 0.0) {
    fail(fmt::format("resolution {} is not a positive number", raster.resolution));
  }
  if (!raster.origin.allFinite()) fail("origin is not finite");
}

// Shortest text that reads back as the same double, always with a decimal
// point or exponent so YAML readers see a float.
std::string yaml_float(double v) {
  std::string s = fmt::format("{}", v);
  if (s.find_first_of(".e") == std::string::npos) s += ".0";
  return s;
}

// Origins are whole cells times the resolution, which binary floating point
// misses by an ulp (-224 * 0.05 = -11.200000000000001): rounded to a
// nanometre, far below any cell, they print as the number meant.
std::string yaml_coordinate(double v) { return yaml_float(std::round(v * 1e9) / 1e9); }

// The file name as a YAML scalar, quoted only if it has to be.
std::string yaml_string(const std::string& s) {
  YAML::Emitter emitter;
  emitter << s;
  return emitter.c_str();
}

std::string encode_pgm(const GridRaster& raster, const MapServerOptions& options) {
  const int unknown = unknown_pixel_for(options);
  std::string header = fmt::format("P5\n{} {}\n255\n", raster.width, raster.height);
  std::string bytes = header;
  bytes.reserve(header.size() + raster.cells.size());
  // The picture's top row is the map's highest y.
  for (int cy = raster.height - 1; cy >= 0; --cy) {
    for (int cx = 0; cx < raster.width; ++cx) {
      const std::int8_t occupancy = occupancy_grid_value(raster.at(cx, cy), options);
      int value = unknown;
      if (occupancy == 100) {
        value = kOccupiedPixel;
      } else if (occupancy == 0) {
        value = kFreePixel;
      }
      if (options.negate) value = 255 - value;
      bytes.push_back(static_cast<char>(static_cast<unsigned char>(value)));
    }
  }
  return bytes;
}

// ---------------------------------------------------------------- reading

class YamlFields {
 public:
  YamlFields(const YAML::Node& root, std::string file) : root_(root), file_(std::move(file)) {}

  [[noreturn]] void fail_at(const YAML::Node& node, const std::string& key, const std::string& what) const {
    throw InputError(fmt::format("{}: line {}: key '{}': {}", file_, node.Mark().line + 1, key, what));
  }

  YAML::Node require(const std::string& key) const {
    const YAML::Node node = root_[key];
    if (!node || node.IsNull()) throw InputError(fmt::format("{}: missing key '{}'", file_, key));
    return node;
  }

  std::string scalar_text(const YAML::Node& node, const std::string& key) const {
    if (!node.IsScalar()) fail_at(node, key, "expected a single value");
    return node.Scalar();
  }

  double number(const YAML::Node& node, const std::string& key) const {
    const std::string text = scalar_text(node, key);
    double value = 0.0;
    try {
      value = node.as<double>();
    } catch (const YAML::Exception&) {
      fail_at(node, key, fmt::format("'{}' is not a number", text));
    }
    if (!std::isfinite(value)) fail_at(node, key, fmt::format("'{}' is not a finite number", text));
    return value;
  }

  double number(const std::string& key) const { return number(require(key), key); }

  bool flag(const std::string& key) const {
    const YAML::Node node = require(key);
    const std::string text = scalar_text(node, key);
    // map_server reads an int and treats any non-zero value as true; ROS 2 writes true/false.
    try {
      return node.as<long>() != 0;
    } catch (const YAML::Exception&) {
    }
    try {
      return node.as<bool>();
    } catch (const YAML::Exception&) {
    }
    fail_at(node, key, fmt::format("'{}' is not 0/1 or true/false", text));
  }

  const std::string& file() const { return file_; }

 private:
  YAML::Node root_;
  std::string file_;
};

YAML::Node load_yaml(const fs::path& yaml_path) {
  std::error_code ec;
  if (!fs::is_regular_file(yaml_path, ec)) {
    throw InputError(fmt::format("{}: map YAML file not found", yaml_path.string()));
  }
  YAML::Node root;
  try {
    root = YAML::LoadFile(yaml_path.string());
  } catch (const YAML::ParserException& e) {
    throw InputError(fmt::format("{}: line {}: invalid YAML: {}", yaml_path.string(), e.mark.line + 1, e.msg));
  } catch (const YAML::Exception& e) {
    throw InputError(fmt::format("{}: cannot read map YAML: {}", yaml_path.string(), e.what()));
  }
  if (!root.IsMap()) {
    throw InputError(fmt::format("{}: expected a map_server YAML mapping (image, resolution, origin, ...)",
                                 yaml_path.string()));
  }
  return root;
}

std::string read_whole_file(const fs::path& path, const std::string& yaml_file, const YAML::Node& image_node) {
  std::error_code ec;
  std::ifstream in(path, std::ios::binary);
  if (!fs::is_regular_file(path, ec) || !in) {
    throw InputError(fmt::format("{}: line {}: key 'image': cannot open image file {}", yaml_file,
                                 image_node.Mark().line + 1, path.string()));
  }
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw InputError(fmt::format("{}: error while reading", path.string()));
  return std::move(buffer).str();
}

enum class MapMode { kTrinary, kScale };

MapMode read_mode(const YamlFields& fields, const YAML::Node& root) {
  const YAML::Node node = root["mode"];
  if (!node || node.IsNull()) return MapMode::kTrinary;  // map_server's default
  const std::string text = fields.scalar_text(node, "mode");
  if (text == "trinary") return MapMode::kTrinary;
  if (text == "scale") return MapMode::kScale;
  if (text == "raw") fields.fail_at(node, "mode", "'raw' maps are not occupancy grids and are not supported");
  fields.fail_at(node, "mode", fmt::format("'{}' is not trinary, scale or raw", text));
}

DsMass mass_for(std::int8_t value) {
  if (value < 0) return DsMass::vacuous();
  const float p = static_cast<float>(value) / 100.0f;
  return p >= 0.5f ? DsMass{2.0f * p - 1.0f, 0.0f} : DsMass{0.0f, 1.0f - 2.0f * p};
}

// The picture's pixels as map_server reads them (rows top down, thresholds,
// negate, scale mode), into occupancy values and masses (rows bottom up).
void fill_cells(const GreyImage& image, MapMode mode, LoadedMap& map) {
  const int width = image.width, height = image.height;
  map.raster.width = width;
  map.raster.height = height;
  map.raster.cells.resize(image.pixels.size());
  map.occupancy.resize(image.pixels.size());
  for (int row = 0; row < height; ++row) {
    const int cy = height - 1 - row;  // picture row 0 is the top = highest y
    for (int cx = 0; cx < width; ++cx) {
      const std::size_t src = static_cast<std::size_t>(row) * width + cx;
      const std::size_t dst = static_cast<std::size_t>(cy) * width + cx;
      double colour = image.pixels[src];
      if (map.options.negate) colour = 255.0 - colour;
      const double occ = (255.0 - colour) / 255.0;
      std::int8_t value = -1;
      if (occ > map.options.occupied_thresh) {
        value = 100;
      } else if (occ < map.options.free_thresh) {
        value = 0;
      } else if (mode == MapMode::kScale) {
        const double ratio = (occ - map.options.free_thresh) / (map.options.occupied_thresh - map.options.free_thresh);
        value = static_cast<std::int8_t>(99.0 * ratio);  // truncation, as map_server's int assignment
      }
      map.occupancy[dst] = value;
      map.raster.cells[dst] = mass_for(value);
    }
  }
}

}  // namespace

void check_map_server_options(const MapServerOptions& o) {
  const bool ordered = o.free_thresh > pixel_occupancy(kFreePixel) && o.free_thresh < o.occupied_thresh &&
                       o.occupied_thresh < pixel_occupancy(kOccupiedPixel);
  if (!ordered) {  // also catches NaN
    throw ConfigError(fmt::format(
        "map_server thresholds: need 1/255 < free_thresh < occupied_thresh < 1 so the map reads back as "
        "written, got free_thresh {} and occupied_thresh {}",
        o.free_thresh, o.occupied_thresh));
  }
}

void write_map_server(const fs::path& yaml_path, const GridRaster& raster, const MapServerOptions& options) {
  OutputFiles files;
  add_map_server(files, yaml_path, raster, options);
  for (const OutputFiles::File& f : files.files()) write_file_atomically(f.path, f.contents);  // image first
}

void add_map_server(OutputFiles& files, const fs::path& yaml_path, const GridRaster& raster,
                    const MapServerOptions& options) {
  check_map_server_options(options);
  check_raster(raster, yaml_path);
  const std::string image_name = yaml_path.stem().string() + ".pgm";
  const fs::path pgm_path = yaml_path.parent_path() / image_name;
  if (yaml_path.stem().empty() || pgm_path == yaml_path) {
    throw InputError(fmt::format("cannot write map {}: need a NAME.yaml path so the image can be NAME.pgm",
                                 yaml_path.string()));
  }

  const std::string yaml = fmt::format(
      "image: {}\n"
      "mode: trinary\n"
      "resolution: {}\n"
      "origin: [{}, {}, 0.0]\n"
      "negate: {}\n"
      "occupied_thresh: {}\n"
      "free_thresh: {}\n",
      yaml_string(image_name), yaml_float(raster.resolution), yaml_coordinate(raster.origin.x()),
      yaml_coordinate(raster.origin.y()), options.negate ? 1 : 0, yaml_float(options.occupied_thresh),
      yaml_float(options.free_thresh));

  // Image first: a YAML that exists always points at a complete picture.
  files.add(pgm_path, encode_pgm(raster, options));
  files.add(yaml_path, yaml);
}

LoadedMap read_map_server(const fs::path& yaml_path) {
  const YAML::Node root = load_yaml(yaml_path);
  const YamlFields fields(root, yaml_path.string());

  LoadedMap map;
  const YAML::Node image_node = fields.require("image");
  const std::string image_text = fields.scalar_text(image_node, "image");
  if (image_text.empty()) fields.fail_at(image_node, "image", "empty file name");

  map.raster.resolution = fields.number("resolution");
  if (map.raster.resolution <= 0.0) {
    fields.fail_at(root["resolution"], "resolution", fmt::format("{} is not positive", map.raster.resolution));
  }

  const YAML::Node origin = fields.require("origin");
  if (!origin.IsSequence() || origin.size() != 3) fields.fail_at(origin, "origin", "expected [x, y, yaw]");
  map.raster.origin = {fields.number(origin[0], "origin"), fields.number(origin[1], "origin")};
  const double yaw = fields.number(origin[2], "origin");
  if (yaw != 0.0) fields.fail_at(origin, "origin", fmt::format("yaw {} is not 0; rotated maps are not supported", yaw));

  map.options.negate = fields.flag("negate");
  map.options.occupied_thresh = fields.number("occupied_thresh");
  map.options.free_thresh = fields.number("free_thresh");
  const MapMode mode = read_mode(fields, root);
  if (mode == MapMode::kScale && !(map.options.occupied_thresh > map.options.free_thresh)) {
    fields.fail_at(root["occupied_thresh"], "occupied_thresh", "scale mode needs occupied_thresh > free_thresh");
  }

  fs::path image_path(image_text);
  if (image_path.is_relative()) image_path = yaml_path.parent_path() / image_path;
  const GreyImage image = parse_pgm(read_whole_file(image_path, fields.file(), image_node), image_path.string());

  fill_cells(image, mode, map);
  return map;
}

}  // namespace dsswarm
