#pragma once
// The file-wide settings of a CARMEN log, from its "# PARAM key value" lines
// (the scan geometry, range limits, laser offset, "odometry none"), and how
// they apply to its laser records against the reader's options. Internal to
// carmen_reader.cpp (not part of carmen_reader.hpp).
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "geometry/pose2.hpp"
#include "io/logs/carmen_fields.hpp"
#include "io/logs/carmen_reader.hpp"

namespace dsswarm::carmen_detail {

class CarmenParams {
 public:
  CarmenParams(const std::string& file, const CarmenOptions& options) : file_(file), options_(options) {}

  // One "# PARAM" line split into fields ("PARAM", key, value...). A bad
  // value is kept aside: an error only where it would be used (check_bad).
  void parse(const Tokens& fields, std::size_t line);
  // Throws InputError for a bad PARAM line the chosen records of `type` use;
  // warns about the others.
  void check_bad(std::string_view type, bool own_geometry, std::vector<std::string>& warnings);

  // Beam layout for a record of n ranges without its own (FLASER/RLASER).
  BeamGeometry beam_geometry(std::size_t n, std::size_t line, std::string_view type) const;
  std::pair<double, double> range_limits() const;  // min, max (m)
  // Options override > `# PARAM` offsets > the offset the first record's
  // poses imply; `implied` holds each record's, checked for a moving laser.
  Pose2 laser_offset(const std::vector<Pose2>& implied, std::vector<std::string>& warnings) const;
  bool no_odometry() const { return params_.no_odometry; }

 private:
  struct Param {
    double value = 0.0;
    std::size_t line = 0;
  };

  struct BadParam {
    std::string key;
    std::size_t line = 0;
    std::string problem;
  };

  struct Params {
    std::optional<Param> angle_min, angle_max, angle_increment, num_beams, range_min, range_max;
    std::optional<Param> offset_x, offset_y, offset_theta;
    bool no_odometry = false;  // "# PARAM odometry none", written by write_carmen

    bool has_geometry() const { return angle_min || angle_max || angle_increment; }
    bool has_offset() const { return offset_x || offset_y || offset_theta; }
  };

  // Parses the value of the PARAM line in fields; says what is wrong with it ("" if nothing).
  std::string problem_of(const Tokens& fields, const std::optional<Param>* slot, double& value) const;
  std::string unused_reason(const std::string& key, std::string_view type, bool own_geometry) const;

  const std::string& file_;
  const CarmenOptions& options_;
  Params params_;
  std::vector<BadParam> bad_params_;
};

}  // namespace dsswarm::carmen_detail
