#include "eval/metrics_json.hpp"

namespace dsswarm {

nlohmann::json to_json(const RelationMetrics& metrics) {
  return {
      {"trans_mean", metrics.trans_mean},     {"trans_std", metrics.trans_std},
      {"rot_mean_deg", metrics.rot_mean_deg}, {"rot_std_deg", metrics.rot_std_deg},
      {"used", metrics.used},                 {"missing", metrics.missing},
  };
}

nlohmann::json to_json(const AteResult& result) {
  return {
      {"ate_rmse", result.rmse}, {"ate_mean", result.mean},  {"ate_median", result.median},
      {"ate_max", result.max},   {"matched", result.matched},
  };
}

}  // namespace dsswarm
