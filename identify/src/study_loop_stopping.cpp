// The iterations of the study loop and when they stop: the tolerance rule of docs/spec.md 3, or
// with stopping.verification_tolerance the stable-answer rule (study_loop_stopping.hpp).
#include <cmath>
#include <cstdio>
#include <limits>

#include "study_loop.hpp"
#include "study_loop_stopping.hpp"

namespace demfit::identify::detail {

double StudyLoop::objective_at(const VectorXd& unit) const {
  for (auto r = runs_.rbegin(); r != runs_.rend(); ++r)
    if (!r->replicate && same_point(r->unit, unit)) return r->objective;
  return std::numeric_limits<double>::quiet_NaN();
}

std::string StudyLoop::stable_answer_note() const {
  if (spec_.verification_tolerance <= 0.0 || std::isnan(verification_gap_)) return {};
  char text[240];
  std::snprintf(text, sizeof text,
                "the verification run's objective is %.3g %% from the surrogate's prediction, %s "
                "stopping.verification_tolerance %.3g %%",
                100.0 * verification_gap_, verification_gap_ <= spec_.verification_tolerance ? "within" : "outside",
                100.0 * spec_.verification_tolerance);
  return text;
}

bool StudyLoop::verification_agrees(int iteration, const VectorXd& optimum, double predicted) {
  const double evaluated = objective_at(optimum);
  verification_gap_ = std::isfinite(evaluated) ? relative_gap(evaluated, predicted, gap_floor_)
                                               : std::numeric_limits<double>::infinity();
  const bool agrees = agrees_with_prediction(evaluated, predicted, gap_floor_, spec_.verification_tolerance);
  if (options_.progress)
    std::fprintf(stderr, "demfit: iteration %d: the verification run %s its prediction (gap %.3g %%, tolerance %.3g %%)\n",
                 iteration, agrees ? "agrees with" : "is far from", 100.0 * verification_gap_,
                 100.0 * spec_.verification_tolerance);
  return agrees;
}

bool StudyLoop::answer_stable(const IterationRecord& record, const VectorXd& previous_optimum,
                              double previous_predicted, double predicted_at_previous) const {
  const double tolerance = spec_.verification_tolerance;
  // The run at the previous prediction agreed with it, and the optimum stopped moving.
  return agrees_with_prediction(objective_at(previous_optimum), previous_predicted, gap_floor_, tolerance) &&
         optimum_settled(record.design_change, spec_.design_tolerance, predicted_at_previous,
                         record.predicted_objective, gap_floor_, tolerance);
}

StudyResult StudyLoop::run() {
  // The cheap level's runs first: the expected-improvement strategy starts from their landscape.
  ask_tell_ = detail::make_study_strategy(spec_, run_cheap_level());
  const Box unit_box = Box::unit(dims_);
  const rbf_surrogate::SrsmSettings srsm{spec_.gamma_pan, spec_.gamma_osc, spec_.eta};
  rbf_surrogate::SrsmState state = rbf_surrogate::srsm_start(detail::initial_region(spec_, variables_));
  const bool stable_rule = spec_.verification_tolerance > 0.0;
  VectorXd previous_optimum;
  double previous_predicted = std::numeric_limits<double>::quiet_NaN();
  double objective_floor = std::numeric_limits<double>::min();
  bool converged = false;
  bool verify_now = false;        // this iteration runs only the verification at previous_optimum
  int verification_iteration = -1;  // set when the loop ends on a verification iteration
  int iteration = 0;
  for (;; ++iteration) {
    const Box region = spec_.strategy == SamplingStrategy::srsm || iteration == 0 ? state.region.box() : unit_box;
    const std::uint64_t seed = detail::iteration_seed(spec_.seed, iteration);
    std::vector<std::string> kinds{"verification"};
    evaluate_points(iteration,
                    verify_now ? MatrixXd(previous_optimum.transpose()) : design(iteration, region, previous_optimum,
                                                                                seed, kinds),
                    kinds);
    // Relative objective changes are measured against at least 1e-12 of the best objective of
    // iteration 0: a noiseless synthetic target drives the objective towards round-off, where
    // relative changes are meaningless. Gaps between a run and its prediction below 1e-6 of it
    // are no news either (the report's verification warning uses the same bound).
    if (iteration == 0) {
      objective_floor = std::max(1e-12 * best_run()->objective, objective_floor);
      gap_floor_ = std::max(1e-6 * best_run()->objective, gap_floor_);
    }
    const bool verified = verify_now;
    if (verify_now) {  // the stable-answer rule's last check
      verify_now = false;
      converged = verification_agrees(iteration, previous_optimum, previous_predicted);
      // Out of iterations or runs: the disagreeing verification ends the loop as the last run.
      if (converged || iteration + 1 >= spec_.max_iterations || budget_reached()) {
        verification_iteration = iteration;
        break;
      }
      if (options_.progress)
        std::fprintf(stderr, "demfit: iteration %d: the verification run joins the data; the loop goes on\n", iteration);
    }
    double predicted_at_previous = std::numeric_limits<double>::quiet_NaN();
    IterationRecord record = optimise(iteration, region, state, seed, previous_optimum, predicted_at_previous);
    const VectorXd optimum = Eigen::Map<const VectorXd>(record.predicted_optimum.data(), dims_);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    record.design_change = iteration == 0 ? nan : (optimum - previous_optimum).cwiseAbs().maxCoeff();
    record.objective_change = iteration == 0 ? nan
                                             : std::abs(record.predicted_objective - previous_predicted) /
                                                   std::max(std::abs(previous_predicted), objective_floor);
    store_.put_iteration(record);
    progress_iteration(iteration, record, region);
    if (stable_rule) {
      verify_now = iteration > 0 && !verified &&
                   answer_stable(record, previous_optimum, previous_predicted, predicted_at_previous);
    } else {  // docs/spec.md 3 stopping rule: design change and objective change both below tolerance.
      converged = iteration > 0 && record.design_change < spec_.design_tolerance &&
                  record.objective_change < spec_.objective_tolerance;
    }
    previous_optimum = optimum;
    previous_predicted = record.predicted_objective;
    if (converged) break;
    // A stable answer is verified next even at the iteration limit, as the final verification
    // always was; the verification run may pass a run budget like it.
    if (!verify_now && (iteration + 1 >= spec_.max_iterations || budget_reached())) break;
    // A verification iteration ran no design: the subregion moves on the next full iteration.
    if (spec_.strategy == SamplingStrategy::srsm && !verified)
      state = rbf_surrogate::srsm_update(state, optimum, srsm, unit_box);
  }
  if (verification_iteration < 0) {
    // Verification run at the final predicted optimum: the answer is always an evaluated point.
    verification_iteration = iteration + 1;
    evaluate_points(verification_iteration, previous_optimum.transpose(), {"verification"});
    if (stable_rule)
      verification_gap_ = relative_gap(objective_at(previous_optimum), previous_predicted, gap_floor_);
  }
  return finish(verification_iteration, converged, state.region.box());
}

}  // namespace demfit::identify::detail
