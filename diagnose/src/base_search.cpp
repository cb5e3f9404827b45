// The base model's criterion chi-square from a surrogate search over the base variables, so that
// base and re-fits are judged at optima found the same way; see fit_context.hpp and
// docs/diagnose.md, step 4.
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "demfit/diagnose/surrogate_start.hpp"
#include "fit_context.hpp"
#include "text_format.hpp"

namespace demfit::diagnose::detail {

void search_base_optimum(const FitContext& c, Diagnosis& d) {
  const int runs = c.options.refit_search_evaluations;
  progress(c.options, c.started, "surrogate search over the base variables (" + std::to_string(runs) + " runs)");
  SurrogateStart s;
  try {
    s = surrogate_search_start(c.model, c.fixed, d.base_variables, d.targets, c.options.fit, runs,
                               c.options.fit.seed, {d.base.values}, {d.base.chi_square});
  } catch (const std::exception& e) {
    d.notes.push_back(std::string("the surrogate search over the base variables failed (") + e.what() +
                      "); the base criterion is its local fit's");
    return;
  }
  d.base_evaluations += s.evaluations;
  d.base_search_evaluations = s.evaluations;
  std::string at;
  identify::ParameterSet point = c.fixed;
  for (std::size_t j = 0; j < d.base_variables.size(); ++j) {
    point[d.base_variables[j].name] = s.values[j];
    at += (j ? ", " : "") + d.base_variables[j].name + " " + format("%.6g", s.values[j]);
  }
  if (s.run_residual.size() == 0) {  // the chosen point is the one told: the base fit's own
    d.notes.push_back("a surrogate search over the base variables (" + std::to_string(s.evaluations) +
                      " runs) predicts its lowest chi-square at the base fit's own point");
    return;
  }
  // Fresh replicas of the searched point, as of the base fit's optimum: their mean is the
  // criterion, and their spread with the search's own run (as many runs as the base's scatter
  // replicas) is the spread at the point that now stands for the base.
  const auto sets = replica_parameter_sets(point, d.base_variables, d.criterion_replicas);
  d.base_evaluations += static_cast<int>(sets.size());
  std::vector<Eigen::VectorXd> runs_at_point{s.run_residual};
  double fresh_sum = 0.0;
  for (auto& r : residuals_at(c.model, sets, d.targets, c.options.fit))
    if (r.size() == s.run_residual.size()) fresh_sum += r.squaredNorm(), runs_at_point.push_back(std::move(r));
  const std::size_t fresh = runs_at_point.size() - 1;
  if (fresh == 0) {
    d.notes.push_back("every replica of the base search's point failed; the base criterion is its local fit's");
    return;
  }
  d.base_search_values = s.values;
  d.base_search_criterion_chi_square = fresh_sum / static_cast<double>(fresh);
  const bool lower = d.base_search_criterion_chi_square < d.base_criterion_chi_square;
  d.notes.push_back(format("a surrogate search over the base variables (%d runs) predicts chi-square %.4g at ",
                           s.evaluations, s.predicted_chi_square) +
                    at + format("; the mean of %zu fresh runs there is %.4g against %.4g at the base fit's optimum: ",
                                fresh, d.base_search_criterion_chi_square, d.base_criterion_chi_square) +
                    (lower ? "the base criterion is the searched point's" : "the base fit's optimum is kept"));
  if (!lower) return;
  d.base_criterion_chi_square = d.base_search_criterion_chi_square;
  // The threshold's spread is the base's (docs/diagnose.md, "model scatter"): now the searched
  // point's, from its own run and the fresh replicas.
  const auto rows = s.run_residual.size();
  d.scatter_chi_square_sd = chi_square_spread(runs_at_point, Eigen::MatrixXd::Identity(rows, rows));
  d.bic_threshold =
      c.options.bic_threshold + 2.0 * std::sqrt(2.0 / d.criterion_replicas) * d.scatter_chi_square_sd;
  d.notes.push_back(format("the chi-square of %zu runs at the searched point spreads by %.3g: an effect must improve "
                           "BIC by %.3g + 2 x sqrt(2/%d) x %.3g = %.3g",
                           runs_at_point.size(), d.scatter_chi_square_sd, c.options.bic_threshold, d.criterion_replicas,
                           d.scatter_chi_square_sd, d.bic_threshold));
}

}  // namespace demfit::diagnose::detail
