#pragma once
// Machine-readable metric summaries (one JSON object each) for scripts and benchmarks.
#include <nlohmann/json.hpp>

#include "eval/ate.hpp"
#include "eval/relations.hpp"

namespace dsswarm {

// Keys: trans_mean, trans_std, rot_mean_deg, rot_std_deg, used, missing.
nlohmann::json to_json(const RelationMetrics& metrics);

// Keys: ate_rmse, ate_mean, ate_median, ate_max, matched.
nlohmann::json to_json(const AteResult& result);

}  // namespace dsswarm
