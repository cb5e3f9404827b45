// Kriging model: Matérn-5/2 correlation, constant mean, maximum-likelihood length scales and nugget
// (formulas in kriging.hpp; Jones, Schonlau & Welch 1998; Rasmussen & Williams 2006, eq. 4.17 for
// the Matérn kernel). The likelihood is minimised with NLopt BOBYQA over log ℓ (and log g), which is
// deterministic, from the default start and, when given, from the previous fit's hyperparameters.
#include "demfit/rbf_surrogate/kriging.hpp"

#include <nlopt.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace demfit::rbf_surrogate {

double matern52(double r) {
  const double s = std::sqrt(5.0) * r;
  return (1.0 + s + s * s / 3.0) * std::exp(-s);
}

double matern52_derivative_over_r(double r) {
  const double s = std::sqrt(5.0) * r;
  return -(5.0 / 3.0) * (1.0 + s) * std::exp(-s);
}

double correlation(KrigingKernel kernel, double r) {
  return kernel == KrigingKernel::gaussian ? std::exp(-0.5 * r * r) : matern52(r);
}

double correlation_derivative_over_r(KrigingKernel kernel, double r) {
  return kernel == KrigingKernel::gaussian ? -std::exp(-0.5 * r * r) : matern52_derivative_over_r(r);
}

namespace {

constexpr double kDefaultLength = 0.3;
constexpr double kFailed = 1e300;

// Everything the likelihood and the prediction need for one (ℓ, g).
struct Factor {
  Eigen::MatrixXd lower;
  VectorXd weights, inverse_ones;
  double ones_inverse_ones = 1.0, mu = 0.0, sigma2 = 1.0, nll = kFailed;
};

Factor factorise(KrigingKernel kernel, const MatrixXd& x, const VectorXd& y, const VectorXd& length, double nugget) {
  const Eigen::Index n = x.rows();
  const MatrixXd xs = x * length.cwiseInverse().asDiagonal();
  MatrixXd r(n, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    r(i, i) = 1.0 + nugget;
    for (Eigen::Index j = 0; j < i; ++j) r(i, j) = r(j, i) = correlation(kernel, (xs.row(i) - xs.row(j)).norm());
  }
  Factor f;
  Eigen::LLT<MatrixXd> llt(r);
  if (llt.info() != Eigen::Success) return f;
  f.lower = llt.matrixL();
  const VectorXd ones = VectorXd::Ones(n);
  f.inverse_ones = llt.solve(ones);
  f.ones_inverse_ones = ones.dot(f.inverse_ones);
  if (!(f.ones_inverse_ones > 0.0)) return f;
  f.mu = f.inverse_ones.dot(y) / f.ones_inverse_ones;
  f.weights = llt.solve(y - f.mu * ones);
  f.sigma2 = std::max((y - f.mu * ones).dot(f.weights) / static_cast<double>(n), 1e-300);
  const double log_det = 2.0 * f.lower.diagonal().array().log().sum();
  f.nll = 0.5 * static_cast<double>(n) * std::log(f.sigma2) + 0.5 * log_det;
  if (!std::isfinite(f.nll)) f.nll = kFailed;
  return f;
}

// Parameter vector θ = [log ℓ_1 .. log ℓ_d, (log g)].
struct Likelihood {
  const MatrixXd* x;
  const VectorXd* y;
  const KrigingOptions* options;
  double fixed_nugget;

  VectorXd length(const std::vector<double>& t) const {
    VectorXd l(x->cols());
    for (Eigen::Index j = 0; j < l.size(); ++j) l[j] = std::exp(t[static_cast<std::size_t>(j)]);
    return l;
  }
  double nugget(const std::vector<double>& t) const {
    return options->estimate_noise ? std::exp(t.back()) : fixed_nugget;
  }
  double operator()(const std::vector<double>& t) const {
    return factorise(options->kernel, *x, *y, length(t), nugget(t)).nll;
  }
};

double likelihood_callback(unsigned n, const double* t, double*, void* data) {
  const auto* l = static_cast<const Likelihood*>(data);
  return (*l)(std::vector<double>(t, t + n));
}

std::vector<double> minimise_likelihood(const Likelihood& l, std::vector<std::vector<double>> starts,
                                        const std::vector<double>& lower, const std::vector<double>& upper,
                                        int budget) {
  std::vector<double> best = starts.front();
  double best_value = l(best);
  for (auto& t : starts) {
    for (std::size_t k = 0; k < t.size(); ++k) t[k] = std::clamp(t[k], lower[k], upper[k]);
    nlopt::opt opt(nlopt::LN_BOBYQA, static_cast<unsigned>(t.size()));
    opt.set_lower_bounds(lower);
    opt.set_upper_bounds(upper);
    opt.set_min_objective(likelihood_callback, const_cast<Likelihood*>(&l));
    opt.set_maxeval(budget);
    opt.set_xtol_abs(1e-3);
    opt.set_initial_step(0.5);
    double value = kFailed;
    try {
      opt.optimize(t, value);
    } catch (const std::exception&) {
      value = l(t);  // roundoff-limited or failed: t still holds the last accepted point
    }
    if (value < best_value) {
      best_value = value;
      best = t;
    }
  }
  return best;
}

void validate_inputs(const MatrixXd& points, const VectorXd& values, const KrigingOptions& o) {
  if (points.rows() != values.size())
    throw std::invalid_argument("KrigingModel::fit: points and values have different numbers of rows");
  if (points.rows() < 2) throw std::invalid_argument("KrigingModel::fit: need at least 2 points");
  if (!points.allFinite() || !values.allFinite())
    throw std::invalid_argument("KrigingModel::fit: points and values must be finite (no NaN or inf)");
  if (!(o.min_length > 0.0 && o.min_length < o.max_length) || !(o.min_nugget > 0.0 && o.min_nugget <= o.max_nugget))
    throw std::invalid_argument("KrigingModel::fit: need 0 < min_length < max_length and 0 < min_nugget <= max_nugget");
  if (o.fixed_hyperparameters && o.length_hint.size() != points.cols())
    throw std::invalid_argument(
        "KrigingModel::fit: fixed_hyperparameters needs a length_hint with one entry per column");
}

}  // namespace

KrigingModel KrigingModel::fit(const MatrixXd& points, const VectorXd& observed, const KrigingOptions& options) {
  validate_inputs(points, observed, options);
  KrigingModel m;
  m.x_ = points;
  m.kernel_ = options.kernel;
  m.trend_ = options.trend;
  VectorXd values = observed;
  if (m.trend_.base) {
    if (m.trend_.base->dims() != points.cols())
      throw std::invalid_argument("KrigingModel::fit: the trend's model has another dimension than the points");
    values -= m.trend_.scale * m.trend_.base->means(points);
  }
  m.y_shift_ = values.mean();
  const double spread = std::sqrt((values.array() - m.y_shift_).square().mean());
  m.y_scale_ = spread > 0.0 ? spread : 1.0;
  const VectorXd y = (values.array() - m.y_shift_) / m.y_scale_;
  const auto d = static_cast<std::size_t>(points.cols());
  const Likelihood l{&m.x_, &y, &options, options.min_nugget};
  std::vector<double> lower(d, std::log(options.min_length)), upper(d, std::log(options.max_length));
  if (options.estimate_noise) {
    lower.push_back(std::log(options.min_nugget));
    upper.push_back(std::log(options.max_nugget));
  }
  std::vector<std::vector<double>> starts;
  std::vector<double> t0(d, std::log(kDefaultLength));
  if (options.estimate_noise) t0.push_back(std::log(std::max(options.min_nugget, 1e-3)));
  if (options.length_hint.size() == points.cols()) {
    std::vector<double> h = t0;
    for (std::size_t j = 0; j < d; ++j) h[j] = std::log(options.length_hint[static_cast<Eigen::Index>(j)]);
    if (options.estimate_noise && options.nugget_hint > 0.0) h.back() = std::log(options.nugget_hint);
    starts.push_back(h);
  }
  std::vector<double> theta;
  if (options.fixed_hyperparameters) {
    theta = starts.front();
  } else {
    starts.push_back(t0);
    const int budget =
        options.likelihood_evaluations > 0 ? options.likelihood_evaluations : 40 * (static_cast<int>(lower.size()) + 1);
    theta = minimise_likelihood(l, starts, lower, upper, budget);
  }
  m.length_ = l.length(theta);
  m.nugget_ = l.nugget(theta);
  Factor f = factorise(m.kernel_, m.x_, y, m.length_, m.nugget_);
  // Near-coincident points can make R + gI numerically indefinite: raise the jitter until it factors.
  for (int k = 0; f.nll >= kFailed && k < 12; ++k) {
    m.nugget_ = std::max(m.nugget_ * 10.0, 1e-10);
    f = factorise(m.kernel_, m.x_, y, m.length_, m.nugget_);
  }
  if (f.nll >= kFailed) throw std::runtime_error("KrigingModel::fit: correlation matrix is not positive definite");
  m.lower_ = std::move(f.lower);
  m.weights_ = std::move(f.weights);
  m.inverse_ones_ = std::move(f.inverse_ones);
  m.ones_inverse_ones_ = f.ones_inverse_ones;
  m.mu_ = f.mu;
  m.sigma2_ = f.sigma2;
  m.nll_ = f.nll;
  return m;
}

VectorXd KrigingModel::correlations(const VectorXd& x) const {
  VectorXd r(x_.rows());
  for (Eigen::Index i = 0; i < x_.rows(); ++i)
    r[i] = correlation(kernel_, (x.transpose() - x_.row(i)).cwiseQuotient(length_.transpose()).norm());
  return r;
}

double KrigingModel::mean(const VectorXd& x, VectorXd* gradient) const {
  if (x.size() != x_.cols()) throw std::invalid_argument("KrigingModel::mean: point has the wrong dimension");
  double value = mu_;
  if (gradient) gradient->setZero(x.size());
  const VectorXd inv_len2 = length_.array().square().inverse();
  for (Eigen::Index i = 0; i < x_.rows(); ++i) {
    const VectorXd diff = x - x_.row(i).transpose();
    const double r = diff.cwiseQuotient(length_).norm();
    value += weights_[i] * correlation(kernel_, r);
    if (gradient) *gradient += weights_[i] * correlation_derivative_over_r(kernel_, r) * diff.cwiseProduct(inv_len2);
  }
  if (gradient) *gradient *= y_scale_;
  double trend = 0.0;
  if (trend_.base) {
    VectorXd trend_gradient;
    trend = trend_.scale * trend_.base->mean(x, gradient ? &trend_gradient : nullptr);
    if (gradient) *gradient += trend_.scale * trend_gradient;
  }
  return y_shift_ + y_scale_ * value + trend;
}

VectorXd KrigingModel::means(const MatrixXd& points) const {
  VectorXd out(points.rows());
  for (Eigen::Index i = 0; i < points.rows(); ++i) out[i] = mean(points.row(i).transpose());
  return out;
}

void KrigingModel::predict(const VectorXd& x, double& mean_value, double& sd) const {
  if (x.size() != x_.cols()) throw std::invalid_argument("KrigingModel::predict: point has the wrong dimension");
  const VectorXd r = correlations(x);
  mean_value = y_shift_ + y_scale_ * (mu_ + r.dot(weights_));
  const VectorXd v = lower_.triangularView<Eigen::Lower>().solve(r);
  const double u = 1.0 - inverse_ones_.dot(r);
  const double s2 = sigma2_ * (1.0 - v.squaredNorm() + u * u / ones_inverse_ones_);
  sd = y_scale_ * std::sqrt(std::max(s2, 0.0));
  if (trend_.base) {
    double base_mean = 0.0, base_sd = 0.0;
    trend_.base->predict(x, base_mean, base_sd);
    mean_value += trend_.scale * base_mean;
    sd = std::sqrt(sd * sd + trend_.scale * trend_.scale * base_sd * base_sd);
  }
}

double KrigingModel::standard_deviation(const VectorXd& x) const {
  double m = 0.0, s = 0.0;
  predict(x, m, s);
  return s;
}

}  // namespace demfit::rbf_surrogate
