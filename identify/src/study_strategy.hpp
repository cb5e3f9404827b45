#pragma once
// Glue between identify's study loop and the ask/tell strategies of rbf_surrogate: the
// "expected_improvement" study strategy. The loop tells every finished iteration (composite
// objective per run, NaN for a failed run, in point order — the order the store replays on resume)
// and asks for the infill points of the next iteration: q = points_per_iteration − 1 batch
// expected-improvement points (kriging believer) on the composite objective; row 0 of each
// iteration stays the loop's predicted optimum of the curve surrogate (all points_per_iteration
// are asked for when that optimum is a run already made).
#include <cstdint>
#include <memory>

#include <Eigen/Dense>

#include "demfit/identify/study_spec.hpp"
#include "demfit/identify/uncertainty.hpp"
#include "demfit/rbf_surrogate/multi_fidelity.hpp"
#include "demfit/rbf_surrogate/strategy.hpp"

namespace demfit::identify::detail {

class StudyStrategy {
 public:
  // `cheap_level`: the cheap level's successful runs (unit coordinates, composite objectives), or
  // none; with them the expensive runs are modelled as rho x cheap + a correction.
  StudyStrategy(const StudySpec& spec, int dims, const rbf_surrogate::FidelityLevel& cheap_level);
  // Results of one iteration (unit coordinates, rows) in point order; NaN = failed run.
  void tell(const Eigen::MatrixXd& unit_points, const Eigen::VectorXd& objectives);
  // Exactly `count` new points (unit coordinates). `planned` rows (e.g. the iteration's predicted
  // optimum) are avoided as if already run; missing ones are filled by maximin (seeded by `seed`).
  Eigen::MatrixXd ask(int count, const Eigen::MatrixXd& planned, std::uint64_t seed);

 private:
  std::unique_ptr<rbf_surrogate::AskTellStrategy> strategy_;
  int dims_;
};

// The ask/tell strategy of a study, or nullptr when the study samples by SRSM or adaptive infill
// (those keep the loop's own iteration).
std::unique_ptr<StudyStrategy> make_study_strategy(const StudySpec& spec,
                                                   const rbf_surrogate::FidelityLevel& cheap_level = {});

}  // namespace demfit::identify::detail

namespace demfit::identify::detail {

// The posterior summary of a finished study (uncertainty.hpp: sample_posterior_from_runs on the
// runs near the best one) as the JSON stored under uncertainty.posterior, plus the pair plot
// posterior_pairs.png in output_dir when `plots` (a reason in `warning` when it could not be drawn).
// Null JSON (and the reason in `warning`) when there are too few runs.
nlohmann::json posterior_json(const StudySpec& spec, const RunSample& sample, const std::filesystem::path& output_dir,
                              bool plots, std::string& warning);

}  // namespace demfit::identify::detail
