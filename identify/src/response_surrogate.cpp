#include "response_surrogate.hpp"

#include <algorithm>
#include <cmath>

namespace demfit::identify::detail {
namespace {

// Finite-difference step in fit-box local coordinates: small against the box, large against
// round-off of the RBF sums.
constexpr double kLocalStep = 1e-5;

Eigen::MatrixXd to_local_rows(const Eigen::MatrixXd& points, const rbf_surrogate::Box& box) {
  Eigen::MatrixXd local(points.rows(), points.cols());
  for (Eigen::Index i = 0; i < points.rows(); ++i) local.row(i) = box.to_local(points.row(i).transpose()).transpose();
  return local;
}

}  // namespace

rbf_surrogate::RbfOptions rbf_options(const StudySpec& spec) {
  rbf_surrogate::RbfOptions options;
  options.basis = spec.basis == "gaussian" ? rbf_surrogate::Basis::gaussian : rbf_surrogate::Basis::multiquadric;
  options.tail = rbf_surrogate::Tail::linear;
  if (spec.smoothing > 0.0) options.fixed_smoothing = spec.smoothing;
  return options;
}

ResponseSurrogate::ResponseSurrogate(const Eigen::MatrixXd& points, const Eigen::MatrixXd& responses,
                                     const rbf_surrogate::Box& fit_box, const StudySpec& spec)
    : fit_box_(fit_box) {
  const Eigen::MatrixXd local = to_local_rows(points, fit_box_);
  principal_components_ = spec.responses == ResponseMode::principal_components;
  if (!principal_components_) {
    network_ = rbf_surrogate::RbfNetwork::fit(local, responses, rbf_options(spec));
    return;
  }
  // PCA of the centred responses; keep the components carrying 99.99 % of the variance.
  mean_ = responses.colwise().mean().transpose();
  const Eigen::MatrixXd centred = responses.rowwise() - mean_.transpose();
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(centred, Eigen::ComputeThinV);
  const Eigen::VectorXd s2 = svd.singularValues().array().square();
  const double total = s2.sum();
  int keep = 1;
  if (total > 0.0) {
    double acc = 0.0;
    for (keep = 0; keep < s2.size();) {
      acc += s2(keep++);
      if (acc >= 0.9999 * total) break;
    }
  }
  keep = std::max(1, keep);
  basis_ = svd.matrixV().leftCols(keep);
  network_ = rbf_surrogate::RbfNetwork::fit(local, centred * basis_, rbf_options(spec));
}

Eigen::VectorXd ResponseSurrogate::predict(const Eigen::VectorXd& unit_x) const {
  const Eigen::VectorXd out = network_.predict(fit_box_.to_local(unit_x));
  if (!principal_components_) return out;
  return mean_ + basis_ * out;
}

double ResponseSurrogate::predicted_objective(const Eigen::VectorXd& unit_x,
                                              const CompositeObjective& objective) const {
  return objective.objective(predict(unit_x));
}

Eigen::VectorXd ResponseSurrogate::objective_gradient(const Eigen::VectorXd& unit_x,
                                                      const CompositeObjective& objective) const {
  const Eigen::Index d = unit_x.size();
  Eigen::VectorXd gradient(d);
  const Eigen::VectorXd width = fit_box_.width();
  for (Eigen::Index j = 0; j < d; ++j) {
    const double h = kLocalStep * width(j);
    Eigen::VectorXd plus = unit_x, minus = unit_x;
    plus(j) += h;
    minus(j) -= h;
    gradient(j) = (predicted_objective(plus, objective) - predicted_objective(minus, objective)) / (2.0 * h);
  }
  return gradient;
}

double ResponseSurrogate::mean_loo_rms() const {
  const Eigen::VectorXd loo = network_.loo_rms();
  return loo.size() ? loo.mean() : 0.0;
}

}  // namespace demfit::identify::detail
