#include "apps/eval_command.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <filesystem>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "eval/ate.hpp"
#include "eval/metrics_json.hpp"
#include "eval/relations.hpp"
#include "eval/swarm_eval.hpp"
#include "io/trajectory/tum.hpp"

namespace dsswarm {

namespace {

// Option storage must outlive add_eval_command(): CLI11 writes into it during
// parsing, and the callbacks (which own it through the shared_ptr) read it.
struct RelationsOptions {
  std::string trajectory;
  std::string relations;
  double max_dt = 0.001;
};

struct SwarmOptions {
  std::string dir;
  std::string relations;
  double max_dt = 0.001;
  std::size_t max_hops = SwarmEvalOptions{}.max_hops;
  double bridge = SwarmEvalOptions{}.bridge;
  bool json = false;
};

struct AteOptions {
  std::string trajectory;
  std::string ground_truth;
  double max_dt = 0.01;
};

void run_relations(const RelationsOptions& o) {
  const Trajectory estimate = read_tum(o.trajectory);
  const std::vector<Relation> relations = read_relations(o.relations);
  const RelationMetrics m = evaluate_relations(estimate, relations, o.max_dt);
  fmt::print("relation metric (Kümmerle et al. 2009): {} against {}\n", o.trajectory, o.relations);
  fmt::print("  translational error: {:.4f} ± {:.4f} m\n", m.trans_mean, m.trans_std);
  fmt::print("  rotational error:    {:.3f} ± {:.3f} deg\n", m.rot_mean_deg, m.rot_std_deg);
  fmt::print("  relations used: {}, missing: {} (max time difference {} s)\n", m.used, m.missing, o.max_dt);
  if (m.missing > 0) {
    fmt::print("warning: {} of {} relations had no trajectory pose near t1 or t2 and were left out\n", m.missing,
               relations.size());
  }
  fmt::print("{}\n", to_json(m).dump());
  std::fflush(stdout);
}

void run_ate(const AteOptions& o) {
  const Trajectory estimate = read_tum(o.trajectory);
  const Trajectory ground_truth = read_tum(o.ground_truth);
  const AteResult r = evaluate_ate(estimate, ground_truth, o.max_dt);
  fmt::print("absolute trajectory error (after rigid SE(2) alignment): {} against {}\n", o.trajectory,
             o.ground_truth);
  fmt::print("  rmse {:.4f} m, mean {:.4f} m, median {:.4f} m, max {:.4f} m\n", r.rmse, r.mean, r.median, r.max);
  fmt::print("  matched poses: {} of {} (max time difference {} s)\n", r.matched, estimate.size(), o.max_dt);
  fmt::print("  alignment: x {:.4f} m, y {:.4f} m, theta {:.3f} deg\n", r.alignment.x, r.alignment.y,
             r.alignment.theta * 180.0 / std::numbers::pi);
  fmt::print("{}\n", to_json(r).dump());
  std::fflush(stdout);
}

void run_swarm(const SwarmOptions& o) {
  const SwarmOutput output = read_swarm_output(o.dir);
  const std::vector<Relation> relations = read_relations(o.relations);
  const SwarmEvaluation ev = evaluate_swarm(output, relations, {o.max_dt, o.max_hops, o.bridge});
  if (o.json) {
    fmt::print("{}\n", to_json(ev).dump(2));
  } else {
    fmt::print("{} against {}\n{}", o.dir, o.relations, format_swarm_evaluation(ev));
  }
  std::fflush(stdout);
}

// CLI11's NonNegativeNumber prints DBL_MAX in full when it fails; say it plainly.
CLI::Validator non_negative_seconds() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        double value = 0.0;
        if (!CLI::detail::lexical_cast(text, value) || !std::isfinite(value) || value < 0.0) {
          return "must be a time in seconds >= 0, got '" + text + "'";
        }
        return {};
      },
      "");
}

}  // namespace

void add_eval_command(CLI::App& app) {
  CLI::App* eval = app.add_subcommand("eval", "Score a trajectory (TUM file) against ground truth");
  eval->require_subcommand(1);

  auto rel = std::make_shared<RelationsOptions>();
  CLI::App* relations_cmd =
      eval->add_subcommand("relations", "Relation metric of Kümmerle et al. 2009 against a .relations file");
  relations_cmd->add_option("trajectory", rel->trajectory, "Estimated trajectory (TUM format)")->required();
  relations_cmd->add_option("relations", rel->relations, "Ground-truth relations file")->required();
  relations_cmd
      ->add_option("--max-dt", rel->max_dt, "Largest accepted time difference between a relation and a pose (s)")
      ->capture_default_str()
      ->check(non_negative_seconds());
  relations_cmd->callback([rel] { run_relations(*rel); });

  auto swarm = std::make_shared<SwarmOptions>();
  CLI::App* swarm_cmd = eval->add_subcommand(
      "swarm", "Score a `dsswarm swarm` output folder: per-agent and cross-agent relations, encounter transforms");
  swarm_cmd->add_option("dir", swarm->dir, "Output folder of `dsswarm swarm`")->required();
  swarm_cmd->add_option("relations", swarm->relations, "Ground-truth relations file of the log played")->required();
  swarm_cmd
      ->add_option("--max-dt", swarm->max_dt, "Largest accepted time difference between a relation and a pose (s)")
      ->capture_default_str()
      ->check(non_negative_seconds());
  swarm_cmd
      ->add_option("--max-hops", swarm->max_hops,
                   "Longest chain of relations accepted as the truth of an encounter")
      ->capture_default_str()
      ->check(CLI::Range(std::size_t{1}, std::size_t{100}));
  swarm_cmd
      ->add_option("--bridge", swarm->bridge,
                   "How far (s) from the exchanged scans an encounter may be checked at relation timestamps (0: never)")
      ->capture_default_str()
      ->check(non_negative_seconds());
  swarm_cmd->add_flag("--json", swarm->json, "Print the evaluation as one JSON object instead of tables");
  swarm_cmd->callback([swarm] { run_swarm(*swarm); });

  auto ate = std::make_shared<AteOptions>();
  CLI::App* ate_cmd = eval->add_subcommand("ate", "Absolute trajectory error against a ground-truth trajectory");
  ate_cmd->add_option("trajectory", ate->trajectory, "Estimated trajectory (TUM format)")->required();
  ate_cmd->add_option("ground_truth", ate->ground_truth, "Ground-truth trajectory (TUM format)")->required();
  ate_cmd->add_option("--max-dt", ate->max_dt, "Largest accepted time difference between associated poses (s)")
      ->capture_default_str()
      ->check(non_negative_seconds());
  ate_cmd->callback([ate] { run_ate(*ate); });
}

}  // namespace dsswarm
