// The model's own scatter as correlated noise; see model_scatter.hpp.
#include "demfit/diagnose/model_scatter.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace demfit::diagnose {

std::vector<TargetScatter> estimate_scatter(const std::vector<Eigen::VectorXd>& replica_residuals,
                                            const std::vector<FitTarget>& targets) {
  if (replica_residuals.size() < 2) throw std::invalid_argument("estimate_scatter: needs at least 2 replicas");
  const Eigen::Index rows = replica_residuals.front().size();
  const auto replicas = static_cast<Eigen::Index>(replica_residuals.size());
  Eigen::MatrixXd r(rows, replicas);
  for (Eigen::Index k = 0; k < replicas; ++k) {
    if (replica_residuals[static_cast<std::size_t>(k)].size() != rows)
      throw std::invalid_argument("estimate_scatter: replicas of different lengths");
    r.col(k) = replica_residuals[static_cast<std::size_t>(k)];
  }
  const Eigen::MatrixXd deviation = r.colwise() - r.rowwise().mean();
  std::vector<TargetScatter> out;
  Eigen::Index offset = 0;
  for (const FitTarget& t : targets) {
    if (t.noise_factor.size() > 0) throw std::logic_error("estimate_scatter: targets must be white (no noise factor)");
    const auto n = static_cast<Eigen::Index>(t.data.x.size());
    // Deviations in y units: the residuals were divided by sigma.
    const Eigen::MatrixXd d = deviation.middleRows(offset, n) * t.sigma;
    offset += n;
    TargetScatter s{t.name, 0.0, 0.0, static_cast<int>(replicas)};
    const double sum_squares = d.squaredNorm();
    // Unbiased about the replicas' mean: replicas - 1 degrees of freedom per point.
    s.sigma = std::sqrt(sum_squares / static_cast<double>((replicas - 1) * std::max<Eigen::Index>(n, 1)));
    if (n > 1 && sum_squares > 0.0) {
      const double lagged = (d.topRows(n - 1).array() * d.bottomRows(n - 1).array()).sum();
      s.lag1 = std::clamp(lagged / sum_squares, 0.0, 0.95);
    }
    out.push_back(s);
  }
  return out;
}

Eigen::MatrixXd scatter_noise_factor(int points, double sigma_data, const TargetScatter& scatter) {
  Eigen::MatrixXd covariance(points, points);
  const double scatter_variance = scatter.sigma * scatter.sigma;
  for (int i = 0; i < points; ++i)
    for (int j = 0; j < points; ++j)
      covariance(i, j) =
          scatter_variance * std::pow(scatter.lag1, std::abs(i - j)) + (i == j ? sigma_data * sigma_data : 0.0);
  const Eigen::LLT<Eigen::MatrixXd> llt(covariance);
  if (llt.info() != Eigen::Success)
    throw std::runtime_error("model scatter: noise covariance is not positive definite");
  return llt.matrixL();
}

std::vector<identify::ParameterSet> replica_parameter_sets(const identify::ParameterSet& base,
                                                           const std::vector<FitVariable>& variables, int replicas) {
  std::vector<identify::ParameterSet> sets;
  for (int k = 1; k <= replicas; ++k) {
    identify::ParameterSet p = base;
    for (const FitVariable& v : variables) {
      const double step = 1e-7 * k * (v.upper - v.lower);
      double& value = p[v.name];
      value = value + step <= v.upper ? value + step : value - step;
    }
    sets.push_back(p);
  }
  return sets;
}

std::vector<FitTarget> with_scatter(const std::vector<FitTarget>& targets, const std::vector<TargetScatter>& scatter,
                                    double threshold, double data_scatter_ratio, std::vector<bool>& whitened) {
  if (!(data_scatter_ratio >= 0.0 && std::isfinite(data_scatter_ratio)))
    throw std::invalid_argument("with_scatter: data_scatter_ratio must be finite and >= 0");
  std::vector<FitTarget> out = targets;
  whitened.assign(targets.size(), false);
  for (std::size_t t = 0; t < out.size() && t < scatter.size(); ++t) {
    if (!(scatter[t].sigma > threshold * out[t].sigma)) continue;
    // Independent trajectories add their variances: sigma_total^2 = (1 + k) sigma_scatter^2.
    TargetScatter in_residual = scatter[t];
    if (data_scatter_ratio > 0.0) in_residual.sigma *= std::sqrt(1.0 + data_scatter_ratio);
    out[t].noise_factor = scatter_noise_factor(static_cast<int>(out[t].data.x.size()), out[t].sigma, in_residual);
    out[t].sigma = std::hypot(out[t].sigma, in_residual.sigma);
    whitened[t] = true;
  }
  return out;
}

double chi_square_spread(const std::vector<Eigen::VectorXd>& replica_residuals,
                         const Eigen::MatrixXd& renormalisation) {
  if (replica_residuals.size() < 2) return 0.0;
  std::vector<double> chi_squares;
  for (const auto& r : replica_residuals) chi_squares.push_back((renormalisation * r).squaredNorm());
  const double mean = std::accumulate(chi_squares.begin(), chi_squares.end(), 0.0) / chi_squares.size();
  double sum = 0.0;
  for (double x : chi_squares) sum += (x - mean) * (x - mean);
  return std::sqrt(sum / static_cast<double>(chi_squares.size() - 1));
}

Eigen::MatrixXd renormalisation(const std::vector<FitTarget>& old_targets, const std::vector<FitTarget>& whitened) {
  if (old_targets.size() != whitened.size()) throw std::invalid_argument("renormalisation: target lists differ");
  Eigen::Index rows = 0;
  for (const auto& t : old_targets) rows += static_cast<Eigen::Index>(t.data.x.size());
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(rows, rows);
  Eigen::Index offset = 0;
  for (std::size_t t = 0; t < old_targets.size(); ++t) {
    if (old_targets[t].noise_factor.size() > 0)
      throw std::logic_error("renormalisation: the old targets must be white (no noise factor)");
    const auto n = static_cast<Eigen::Index>(old_targets[t].data.x.size());
    Eigen::MatrixXd block = Eigen::MatrixXd::Identity(n, n) * old_targets[t].sigma;  // back to y units
    if (whitened[t].noise_factor.size() > 0)
      block = whitened[t].noise_factor.triangularView<Eigen::Lower>().solve(block);
    else
      block /= whitened[t].sigma;
    a.block(offset, offset, n, n) = block;
    offset += n;
  }
  return a;
}

}  // namespace demfit::diagnose
