// Bounded Levenberg-Marquardt on model evaluations; see least_squares.hpp.
#include "demfit/diagnose/least_squares.hpp"

#include "demfit/identify/evaluator.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "demfit/identify/objective.hpp"

namespace demfit::diagnose {

std::vector<std::vector<double>> raw_residuals(const identify::CurveSet& curves, const std::vector<FitTarget>& targets) {
  std::vector<std::vector<double>> out;
  for (const auto& t : targets) {
    const auto found = curves.find(t.curve);
    if (found == curves.end()) throw std::runtime_error("the model produced no curve '" + t.curve + "'");
    std::vector<double> r = identify::resample_monotone(found->second, t.data.x);
    for (std::size_t i = 0; i < r.size(); ++i) {
      r[i] -= t.data.y[i];
      if (!std::isfinite(r[i])) throw std::runtime_error("curve '" + t.curve + "' contains a non-finite value");
    }
    out.push_back(std::move(r));
  }
  return out;
}

Eigen::VectorXd normalised_residual(const identify::CurveSet& curves, const std::vector<FitTarget>& targets) {
  const auto raw = raw_residuals(curves, targets);
  std::size_t size = 0;
  for (const auto& r : raw) size += r.size();
  Eigen::VectorXd out(static_cast<Eigen::Index>(size));
  Eigen::Index k = 0;
  for (std::size_t t = 0; t < raw.size(); ++t)
    for (double v : raw[t]) out(k++) = v / targets[t].sigma;
  return out;
}

std::vector<identify::CurveSet> evaluate_many(const identify::Model& model,
                                              const std::vector<identify::ParameterSet>& sets, int jobs,
                                              unsigned long seed) {
  // The identify thread pool: same scheduling, failure capture and ordering as a study's runs.
  identify::ThreadPoolEvaluator evaluator(model, jobs, 1, seed);
  std::vector<identify::CurveSet> out;
  for (auto& outcome : evaluator.evaluate_batch(sets, nullptr)) {
    out.push_back(outcome.ok ? std::move(outcome.curves) : identify::CurveSet{});  // empty: failed run
  }
  return out;
}

std::vector<Eigen::VectorXd> residuals_at(const identify::Model& model, const std::vector<identify::ParameterSet>& sets,
                                          const std::vector<FitTarget>& targets, const FitOptions& options) {
  std::vector<Eigen::VectorXd> out;
  for (const auto& curves : evaluate_many(model, sets, options.jobs, options.seed)) {
    Eigen::VectorXd r;
    if (!curves.empty()) {
      try { r = normalised_residual(curves, targets); } catch (const std::exception&) { r.resize(0); }
    }
    out.push_back(r);
  }
  return out;
}

namespace {

struct Problem {
  const identify::Model& model;
  const identify::ParameterSet& fixed;
  const std::vector<FitVariable>& variables;
  const std::vector<FitTarget>& targets;
  const FitOptions& options;
  int evaluations = 0;

  identify::ParameterSet parameters(const Eigen::VectorXd& u) const {
    identify::ParameterSet p = fixed;
    for (std::size_t j = 0; j < variables.size(); ++j)
      p[variables[j].name] = variables[j].lower + u(j) * (variables[j].upper - variables[j].lower);
    return p;
  }
  // Residuals at several normalised points; an empty vector marks a failed evaluation.
  std::vector<Eigen::VectorXd> residuals(const std::vector<Eigen::VectorXd>& points) {
    std::vector<identify::ParameterSet> sets;
    for (const auto& u : points) sets.push_back(parameters(u));
    evaluations += static_cast<int>(points.size());
    return residuals_at(model, sets, targets, options);
  }
};

// Forward differences in normalised coordinates (backwards at the upper bound).
Eigen::MatrixXd jacobian(Problem& problem, const Eigen::VectorXd& u, const Eigen::VectorXd& r) {
  const Eigen::Index n = u.size();
  std::vector<Eigen::VectorXd> points;
  std::vector<double> steps;
  for (Eigen::Index j = 0; j < n; ++j) {
    const double h = u(j) + problem.options.fd_step > 1.0 ? -problem.options.fd_step : problem.options.fd_step;
    Eigen::VectorXd p = u;
    p(j) += h;
    points.push_back(p);
    steps.push_back(h);
  }
  const auto rs = problem.residuals(points);
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(r.size(), n);
  for (Eigen::Index j = 0; j < n; ++j)
    if (rs[j].size() == r.size()) J.col(j) = (rs[j] - r) / steps[j];
  return J;
}

}  // namespace

FitResult fit_least_squares(const identify::Model& model, const identify::ParameterSet& fixed,
                            const std::vector<FitVariable>& variables, const std::vector<FitTarget>& targets,
                            const FitOptions& options) {
  Problem problem{model, fixed, variables, targets, options};
  const Eigen::Index n = static_cast<Eigen::Index>(variables.size());
  Eigen::VectorXd u(n);
  for (Eigen::Index j = 0; j < n; ++j) {
    const auto& v = variables[j];
    u(j) = std::clamp((v.start - v.lower) / (v.upper - v.lower), 0.0, 1.0);
  }
  Eigen::VectorXd r = problem.residuals({u}).front();
  if (r.size() == 0) throw std::runtime_error("least-squares fit: the model cannot be evaluated at the start point");
  double cost = r.squaredNorm();
  double lambda = 1e-3;
  int iteration = 0;
  for (; iteration < options.max_iterations && n > 0; ++iteration) {
    const Eigen::MatrixXd J = jacobian(problem, u, r);
    const Eigen::MatrixXd JtJ = J.transpose() * J;
    const Eigen::VectorXd g = J.transpose() * r;
    bool accepted = false;
    double new_cost = cost;
    for (int attempt = 0; attempt < 12 && !accepted; ++attempt) {
      Eigen::MatrixXd A = JtJ;
      for (Eigen::Index j = 0; j < n; ++j) A(j, j) += lambda * std::max(JtJ(j, j), 1e-12);
      const Eigen::VectorXd step = A.ldlt().solve(-g);
      const Eigen::VectorXd trial = (u + step).cwiseMax(0.0).cwiseMin(1.0);
      const Eigen::VectorXd rt = problem.residuals({trial}).front();
      if (rt.size() == r.size() && rt.squaredNorm() < cost) {
        u = trial;
        r = rt;
        new_cost = rt.squaredNorm();
        accepted = true;
        lambda = std::max(lambda / 3.0, 1e-9);
      } else {
        lambda *= 4.0;
      }
    }
    if (!accepted) break;
    const double decrease = cost - new_cost;
    cost = new_cost;
    if (decrease <= options.relative_tolerance * cost) { ++iteration; break; }
  }
  FitResult result;
  result.parameters = problem.parameters(u);
  for (Eigen::Index j = 0; j < n; ++j) result.values.push_back(result.parameters.at(variables[j].name));
  result.chi_square = cost;
  result.residual = r;
  result.evaluations = problem.evaluations;
  result.iterations = iteration;
  return result;
}

}  // namespace demfit::diagnose
