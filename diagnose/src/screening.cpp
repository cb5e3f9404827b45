// Score-test screening of candidate effects; see screening.hpp.
#include "demfit/diagnose/screening.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "demfit/diagnose/residual_tests.hpp"

namespace demfit::diagnose {
namespace {

// Step away from `from` by `fraction` of [lower, upper], towards the interior.
double step_inside(double from, double lower, double upper, double fraction) {
  const double h = fraction * (upper - lower);
  return from + h <= upper ? h : -h;
}

}  // namespace

std::vector<ScreeningScore> screen_candidates(const identify::Model& model, const FitResult& base,
                                              const std::vector<FitVariable>& variables,
                                              const std::vector<FitTarget>& targets,
                                              const std::vector<EffectCandidate>& candidates, double step,
                                              const FitOptions& options, int* evaluations) {
  const Eigen::VectorXd& r = base.residual;
  // The base variables' sensitivities are the base fit's final Jacobian (no evaluation).
  if (base.jacobian.rows() != r.size() || base.jacobian.cols() != static_cast<Eigen::Index>(variables.size()))
    throw std::logic_error("screen_candidates: the base fit carries no Jacobian of its variables");
  // One batch: every effect parameter switched on by `step` of its range.
  std::vector<identify::ParameterSet> sets;
  std::vector<double> steps;
  for (const auto& c : candidates)
    for (const auto& e : c.parameters) {
      identify::ParameterSet p = base.parameters;
      const double h = step_inside(e.off_value, e.lower, e.upper, step);
      p[e.name] = e.off_value + h;
      sets.push_back(p);
      steps.push_back(h);
    }
  const auto rs = residuals_at(model, sets, targets, options);
  if (evaluations) *evaluations = static_cast<int>(sets.size());
  // Only base variables free at the optimum can absorb a change: one held at a bound cannot move
  // outwards, and the residual is not orthogonal to its column, so it is left out of the span.
  std::vector<Eigen::VectorXd> free_columns;
  for (std::size_t j = 0; j < variables.size(); ++j)
    if (!at_bound(variables[j], base.parameters.at(variables[j].name)))
      free_columns.push_back(base.jacobian.col(static_cast<Eigen::Index>(j)));
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(r.size(), static_cast<Eigen::Index>(free_columns.size()));
  for (std::size_t j = 0; j < free_columns.size(); ++j) J.col(static_cast<Eigen::Index>(j)) = free_columns[j];
  // (Eigen's decompositions do not accept a matrix without columns: every variable at a bound.)
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> base_span;
  if (!free_columns.empty()) base_span.compute(J);

  std::vector<ScreeningScore> scores;
  std::size_t k = 0;
  for (const auto& c : candidates) {
    ScreeningScore s;
    s.effect = c.name;
    const Eigen::Index m = static_cast<Eigen::Index>(c.parameters.size());
    Eigen::MatrixXd S(r.size(), m);
    const std::size_t first = k;  // this candidate's entries in sets/steps/rs
    for (Eigen::Index j = 0; j < m; ++j, ++k) {
      if (rs[k].size() != r.size()) {
        s.evaluated = false;
        S.col(j).setZero();
        continue;
      }
      S.col(j) = (rs[k] - r) / steps[k];
    }
    s.sensitivity = S;
    // What the base variables can already absorb is no evidence for the effect: project it out.
    const Eigen::MatrixXd S_perp = free_columns.empty() ? S : Eigen::MatrixXd(S - J * base_span.solve(S));
    const Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> effect_span(S_perp);
    const Eigen::VectorXd beta = -effect_span.solve(r);  // r + S beta ~ 0
    s.score = (S_perp * beta).squaredNorm();
    s.p_value = chi_square_upper_p(s.score, static_cast<double>(m));
    s.fraction_explained = r.squaredNorm() > 0.0 ? s.score / r.squaredNorm() : 0.0;
    s.absorbed_by_base =
        S.squaredNorm() > 0.0 ? std::clamp(1.0 - S_perp.squaredNorm() / S.squaredNorm(), 0.0, 1.0) : 0.0;
    for (Eigen::Index j = 0; j < m; ++j) {
      const auto& e = c.parameters[j];
      s.start.push_back(std::clamp(e.off_value + beta(j), e.lower, e.upper));
      // From the off value to the far end of the range, on the side the screening stepped to.
      const double reach =
          steps[first + static_cast<std::size_t>(j)] > 0.0 ? e.upper - e.off_value : e.lower - e.off_value;
      s.full_range_gain = std::max(s.full_range_gain, S_perp.col(j).squaredNorm() * reach * reach);
    }
    scores.push_back(s);
  }
  return scores;
}

}  // namespace demfit::diagnose
