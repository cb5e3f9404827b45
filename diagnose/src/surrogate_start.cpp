// A re-fit start from a surrogate search over base + effect variables; see surrogate_start.hpp.
#include "demfit/diagnose/surrogate_start.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "demfit/rbf_surrogate/bounds.hpp"
#include "demfit/rbf_surrogate/expensive.hpp"
#include "demfit/rbf_surrogate/kriging.hpp"
#include "demfit/rbf_surrogate/strategy.hpp"

namespace demfit::diagnose {

namespace {

// Points asked per round, whatever fit.jobs is (they are run fit.jobs at a time): the points
// asked, and so the result, must not depend on how many cores run them.
constexpr int kBatch = 2;

std::vector<rbf_surrogate::Variable> design_variables(const std::vector<FitVariable>& variables) {
  std::vector<rbf_surrogate::Variable> out;
  for (const FitVariable& v : variables) out.push_back({v.name, v.lower, v.upper, false});
  return out;
}

identify::ParameterSet parameters_at(const identify::ParameterSet& fixed, const std::vector<FitVariable>& variables,
                                     const Eigen::VectorXd& physical) {
  identify::ParameterSet p = fixed;
  for (std::size_t j = 0; j < variables.size(); ++j) p[variables[j].name] = physical[static_cast<Eigen::Index>(j)];
  return p;
}

// The strategy: a maximin design of 5 points per variable (the known points count towards it),
// then expected improvement on a kriging model with an estimated nugget (a run's chi-square is one
// trajectory's), its values log-warped when more likely (chi-squares span decades).
rbf_surrogate::ExpensiveOptions search_options(int dims, std::uint64_t seed) {
  rbf_surrogate::ExpensiveOptions o;
  o.strategy = rbf_surrogate::InfillStrategy::expected_improvement;
  o.seed = seed;
  o.initial_points = 5 * dims;
  o.kriging.estimate_noise = true;
  return o;
}

}  // namespace

SurrogateStart surrogate_search_start(const identify::Model& model, const identify::ParameterSet& fixed,
                                      const std::vector<FitVariable>& variables, const std::vector<FitTarget>& targets,
                                      const FitOptions& fit, int evaluations, std::uint64_t seed,
                                      const std::vector<std::vector<double>>& known_values,
                                      const std::vector<double>& known_chi_squares) {
  const auto dims = static_cast<int>(variables.size());
  if (dims < 1) throw std::invalid_argument("surrogate_search_start: no variables");
  if (known_values.size() != known_chi_squares.size())
    throw std::invalid_argument("surrogate_search_start: known points and chi-squares differ in number");
  const std::vector<rbf_surrogate::Variable> design = design_variables(variables);
  auto strategy = rbf_surrogate::make_strategy(dims, search_options(dims, seed));
  for (std::size_t i = 0; i < known_values.size(); ++i) {
    if (known_values[i].size() != variables.size() || !std::isfinite(known_chi_squares[i])) continue;
    const Eigen::VectorXd unit = rbf_surrogate::to_unit(
        design, Eigen::Map<const Eigen::VectorXd>(known_values[i].data(), static_cast<Eigen::Index>(dims)));
    if (!strategy->history().is_new(unit)) continue;
    strategy->tell(unit.transpose(), Eigen::VectorXd::Constant(1, known_chi_squares[i]));
  }
  SurrogateStart out;
  std::vector<std::pair<Eigen::VectorXd, Eigen::VectorXd>> runs;  // unit point, its residual
  while (out.evaluations < evaluations) {
    Eigen::MatrixXd asked = strategy->ask(kBatch);
    asked.conservativeResize(std::min<Eigen::Index>(asked.rows(), evaluations - out.evaluations), Eigen::NoChange);
    std::vector<identify::ParameterSet> sets;
    for (Eigen::Index i = 0; i < asked.rows(); ++i)
      sets.push_back(parameters_at(fixed, variables, rbf_surrogate::from_unit(design, asked.row(i).transpose())));
    const std::vector<Eigen::VectorXd> residuals = residuals_at(model, sets, targets, fit);
    Eigen::VectorXd chi_squares(asked.rows());
    for (Eigen::Index i = 0; i < asked.rows(); ++i) {
      const Eigen::VectorXd& r = residuals[static_cast<std::size_t>(i)];
      chi_squares[i] = r.size() > 0 && r.allFinite() ? r.squaredNorm() : std::numeric_limits<double>::quiet_NaN();
      if (std::isfinite(chi_squares[i])) runs.emplace_back(asked.row(i).transpose(), r);
    }
    strategy->tell(asked, chi_squares);
    out.evaluations += static_cast<int>(asked.rows());
  }
  const auto& history = strategy->history();
  if (history.successes() < 3)
    throw std::runtime_error("surrogate search: fewer than 3 of its runs succeeded; nothing to model");
  // The run point of lowest predicted mean of a noisy kriging model of log chi-square: the values
  // are positive and span decades, and the nugget takes up one trajectory's scatter.
  const Eigen::MatrixXd points = history.fit_points();
  const Eigen::VectorXd values = history.fit_values();
  rbf_surrogate::KrigingOptions smooth;
  smooth.estimate_noise = true;
  const Eigen::VectorXd logs = values.array().max(1e-300).log().matrix();
  const auto kriging = rbf_surrogate::KrigingModel::fit(points, logs, smooth);
  const Eigen::VectorXd means = kriging.means(points);
  Eigen::Index best = 0;
  means.minCoeff(&best);
  const Eigen::VectorXd physical = rbf_surrogate::from_unit(design, points.row(best).transpose());
  out.values.assign(physical.data(), physical.data() + physical.size());
  out.predicted_chi_square = std::exp(means[best]);
  out.run_chi_square = values[best];
  const Eigen::VectorXd chosen = points.row(best).transpose();
  for (const auto& [unit, residual] : runs)
    if (unit == chosen) out.run_residual = residual;
  return out;
}

}  // namespace demfit::diagnose
