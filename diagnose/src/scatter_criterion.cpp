// The scatter-aware criterion of a diagnosis (fit_context.hpp; docs/diagnose.md "model scatter"):
// replicas of an optimum, the whitened noise model and the base fit refined under it.
#include <algorithm>
#include <cmath>

#include "fit_context.hpp"
#include "text_format.hpp"

namespace demfit::diagnose::detail {
namespace {

// The mean chi-square of the non-empty (not failed) `residuals`, each mapped by `map` (none: as
// they are); `fallback` if there is none.
double mean_chi_square(const std::vector<Eigen::VectorXd>& residuals, const Eigen::MatrixXd* map, double fallback) {
  double sum = 0.0;
  int runs = 0;
  for (const auto& r : residuals)
    if (r.size() > 0) {
      sum += map ? (*map * r).squaredNorm() : r.squaredNorm();
      ++runs;
    }
  return runs > 0 ? sum / runs : fallback;
}

// The base fit refined under the whitened targets from its optimum; the first optimum, mapped by
// `a`, is kept if the refinement fails or does not improve on it.
void refine_base(const FitContext& c, Diagnosis& d, const Eigen::MatrixXd& a) {
  FitResult carried = d.base;
  carried.residual = a * d.base.residual;
  carried.jacobian = a * d.base.jacobian;
  carried.chi_square = carried.residual.squaredNorm();
  std::vector<FitVariable> vars = d.base_variables;
  for (std::size_t j = 0; j < vars.size(); ++j) vars[j].start = d.base.values[j];
  const FitOptions fit = stage_fit_options(c.options, c.started, "base fit under the scatter noise model");
  try {
    FitResult refined = fit_least_squares(c.model, c.fixed, vars, d.targets, fit, &carried.jacobian);
    d.base_evaluations += refined.evaluations;
    d.base = refined.chi_square < carried.chi_square ? std::move(refined) : std::move(carried);
  } catch (const std::exception& e) {
    d.notes.push_back(std::string("base fit under the scatter noise model failed (") + e.what() +
                      "); the first base optimum is kept");
    d.base = std::move(carried);
  }
}

}  // namespace

double replicated_chi_square(const FitContext& c, const identify::ParameterSet& optimum,
                             const std::vector<FitVariable>& variables, const std::vector<FitTarget>& targets,
                             int replicas, double fallback, int& evaluations) {
  const auto sets = replica_parameter_sets(optimum, variables, replicas);
  evaluations += static_cast<int>(sets.size());
  return mean_chi_square(residuals_at(c.model, sets, targets, c.options.fit), nullptr, fallback);
}

void account_for_scatter(const FitContext& c, Diagnosis& d) {
  const auto sets = replica_parameter_sets(d.base.parameters, d.base_variables, c.options.scatter_replicas);
  std::vector<Eigen::VectorXd> replicas{d.base.residual};
  for (auto& r : residuals_at(c.model, sets, d.targets, c.options.fit))
    if (r.size() == d.base.residual.size()) replicas.push_back(std::move(r));
  d.base_evaluations += static_cast<int>(sets.size());
  if (replicas.size() < 2) {
    d.notes.push_back("model scatter not measured: every replica run failed; data noise alone is used");
    return;
  }
  d.scatter = estimate_scatter(replicas, d.targets);
  std::vector<bool> whitened;
  std::vector<FitTarget> targets = with_scatter(d.targets, d.scatter, c.options.scatter_threshold,
                                                   c.options.data_scatter_ratio, whitened);
  for (std::size_t t = 0; t < targets.size(); ++t)
    d.notes.push_back(format(
        "target '%s': model scatter %.4g (lag-1 correlation %.3f, %d runs) against data noise %.4g: %s",
        d.targets[t].name.c_str(), d.scatter[t].sigma, d.scatter[t].lag1, d.scatter[t].replicas, d.targets[t].sigma,
        scatter_use(whitened[t], c.options.data_scatter_ratio).c_str()));
  d.scatter_in_noise_model = std::find(whitened.begin(), whitened.end(), true) != whitened.end();
  progress(c.options, c.started,
           format("model scatter measured from %zu runs%s", replicas.size(),
                  d.scatter_in_noise_model ? ": residuals whitened, refining the base fit" : ": negligible"));
  if (!d.scatter_in_noise_model) return;
  const Eigen::MatrixXd a = renormalisation(d.targets, targets);
  // Every evaluation draws its own trajectory, so one run's chi-square carries the spread of the
  // replicas' chi-squares, and a fit over dozens of evaluations keeps a lucky one. The criterion
  // therefore compares means over R fresh replicas of each optimum (base and re-fits): a difference
  // of two such means is noisy by about sqrt(2 / R) x that spread (the base's; at a better fit the
  // spread is smaller, as the cross term with the systematic residual shrinks), and an effect must
  // beat the threshold by two such standard deviations. With the single kept run and
  // sqrt(2) instead, a wall friction of 0.014 (physically nothing) gained delta BIC 17 by trajectory
  // luck on the frictionless s = 4 drum; with wall friction in the drum, the true rolling
  // friction's re-fit (RMS/sigma 3.06 -> 1.06) gained 54 against a threshold of 83 and nothing could
  // be named.
  d.scatter_chi_square_sd = chi_square_spread(replicas, a);
  d.criterion_replicas = c.options.scatter_replicas;
  const double difference_sd = std::sqrt(2.0 / d.criterion_replicas) * d.scatter_chi_square_sd;
  d.bic_threshold = c.options.bic_threshold + 2.0 * difference_sd;
  d.targets = std::move(targets);
  const identify::ParameterSet first_optimum = d.base.parameters;
  refine_base(c, d, a);
  d.base_refined = !(d.base.parameters == first_optimum);
  if (!d.base_refined) {
    // The refinement kept the first optimum: its replicas above (all but the base's own run) are
    // the fresh runs, so no new ones are needed.
    d.base_criterion_chi_square = mean_chi_square({replicas.begin() + 1, replicas.end()}, &a, d.base.chi_square);
  } else {
    d.base_criterion_chi_square = replicated_chi_square(c, d.base.parameters, d.base_variables, d.targets,
                                                        d.criterion_replicas, d.base.chi_square, d.base_evaluations);
  }
  d.notes.push_back(format(
      "the chi-square of %zu runs differing only in round-off spreads by %.3g (standard deviation); the criterion "
      "compares means over %d fresh runs of each optimum (base: %.4g, against %.4g for the fit's own run), so an "
      "effect must improve BIC by %.3g + 2 x sqrt(2/%d) x %.3g = %.3g",
      replicas.size(), d.scatter_chi_square_sd, d.criterion_replicas, d.base_criterion_chi_square, d.base.chi_square,
      c.options.bic_threshold, d.criterion_replicas, d.scatter_chi_square_sd, d.bic_threshold));
}

}  // namespace demfit::diagnose::detail
