// RBF network fit (width and smoothing search) and analytic prediction.
#include "demfit/rbf_surrogate/rbf_network.hpp"

#include "rbf_spectral.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace demfit::rbf_surrogate {

namespace {

using detail::Prepared;
using detail::Spectrum;

struct Choice {
  double width = 0.0;
  double smoothing = 0.0;  // absolute
  double value = std::numeric_limits<double>::infinity();
};

// Golden-section search on [a, b] for a unimodal-in-the-bracket f; returns (argmin, min), also
// considering the end points so a bracket from a grid never loses its best grid value.
template <class F>
std::pair<double, double> golden_section(F f, double a, double b, double fa, double fb, int iterations) {
  constexpr double g = 0.6180339887498949;
  double best_x = fa <= fb ? a : b, best_f = std::min(fa, fb);
  double x1 = b - g * (b - a), x2 = a + g * (b - a);
  double f1 = f(x1), f2 = f(x2);
  for (int it = 0; it < iterations; ++it) {
    if (f1 <= f2) {
      b = x2;
      x2 = x1;
      f2 = f1;
      x1 = b - g * (b - a);
      f1 = f(x1);
    } else {
      a = x1;
      x1 = x2;
      f1 = f2;
      x2 = a + g * (b - a);
      f2 = f(x2);
    }
  }
  if (f1 < best_f) {
    best_x = x1;
    best_f = f1;
  }
  if (f2 < best_f) {
    best_x = x2;
    best_f = f2;
  }
  return {best_x, best_f};
}

// Grid scan of f over [lo, hi] (n points), then golden refinement between the best point's
// neighbours: a bracketed 1-D search robust to the criterion's occasional secondary minima.
template <class F>
std::pair<double, double> bracketed_minimum(F f, double lo, double hi, int grid, int iterations) {
  std::vector<double> xs(grid), fs(grid);
  int best = 0;
  for (int i = 0; i < grid; ++i) {
    xs[i] = lo + (hi - lo) * i / (grid - 1);
    fs[i] = f(xs[i]);
    if (fs[i] < fs[best]) best = i;
  }
  if (!std::isfinite(fs[best])) return {xs[best], fs[best]};
  const int l = std::max(best - 1, 0), r = std::min(best + 1, grid - 1);
  return golden_section(f, xs[l], xs[r], fs[l], fs[r], iterations);
}

// Best ridge term for one width. The ridge is searched relative to the kernel's spectral scale,
// log10(λ/scale) in [-10, 0]: below 1e-10 it is indistinguishable from interpolation.
Choice best_smoothing(const Prepared& prepared, const Spectrum& s, const RbfOptions& options) {
  Choice c;
  c.width = s.width;
  if (options.fixed_smoothing) {
    c.smoothing = *options.fixed_smoothing * s.scale;
    c.value = detail::criterion(prepared, s, c.smoothing);
    return c;
  }
  if (!options.smoothing) {
    c.value = detail::criterion(prepared, s, 0.0);
    return c;
  }
  auto f = [&](double log_mu) { return detail::criterion(prepared, s, std::pow(10.0, log_mu) * s.scale); };
  const auto [log_mu, value] = bracketed_minimum(f, -10.0, 0.0, 11, 10);
  c.smoothing = std::pow(10.0, log_mu) * s.scale;
  c.value = value;
  return c;
}

Choice search(const Prepared& prepared, const RbfOptions& options) {
  if (!detail::uses_width(options.basis)) return best_smoothing(prepared, detail::spectrum(prepared, 0.0), options);
  if (options.fixed_width) return best_smoothing(prepared, detail::spectrum(prepared, *options.fixed_width), options);
  // Widths from a twentieth of the typical spacing to several design diameters (log scale), or a
  // factor 8 either side of a hint.
  double lo = std::log(0.05 * prepared.nearest_mean), hi = std::log(5.0 * prepared.diameter);
  // 16 log-spaced widths (steps of a factor ~1.7), then 10 golden steps: 1 % width resolution,
  // far below the criterion's flatness near its minimum.
  int grid = 16;
  if (options.width_hint && *options.width_hint > 0.0 && std::isfinite(*options.width_hint)) {
    lo = std::log(*options.width_hint / 8.0);
    hi = std::log(*options.width_hint * 8.0);
    grid = 9;
  }
  Choice best;
  auto f = [&](double log_width) {
    const Choice c = best_smoothing(prepared, detail::spectrum(prepared, std::exp(log_width)), options);
    if (c.value < best.value) best = c;
    return c.value;
  };
  bracketed_minimum(f, lo, hi, grid, 10);
  return best;
}

Choice choose_width(const Prepared& prepared, const RbfOptions& options) {
  Choice best = search(prepared, options);
  if (!std::isfinite(best.value) && !options.smoothing && !options.fixed_smoothing) {
    // Nearly coincident points make pure interpolation singular; a ridge term chosen by the same
    // criterion is the least-biased way to still return a model.
    RbfOptions ridge = options;
    ridge.smoothing = true;
    best = search(prepared, ridge);
  }
  if (!std::isfinite(best.value))
    throw std::invalid_argument(
        "RBF fit: the system is singular for every width and smoothing; check for "
        "near-duplicate points");
  return best;
}

}  // namespace

RbfNetwork RbfNetwork::fit(const MatrixXd& points, const MatrixXd& values, const RbfOptions& options) {
  const Prepared prepared = detail::prepare(points, values, options);
  const Choice choice = choose_width(prepared, options);
  RbfNetwork net;
  net.options_ = options;
  net.centers_ = points;
  net.width_ = choice.width;
  net.smoothing_ = choice.smoothing;
  net.criterion_value_ = choice.value;
  const Spectrum s = detail::spectrum(prepared, choice.width);
  detail::solve(prepared, s, values, choice.smoothing, net.alpha_, net.beta_, net.loo_residuals_);
  return net;
}

namespace {

void check_point(const VectorXd& x, int dims) {
  if (x.size() != dims)
    throw std::invalid_argument("RBF predict: point has " + std::to_string(x.size()) +
                                " coordinates, the "
                                "network has " +
                                std::to_string(dims));
}

}  // namespace

VectorXd RbfNetwork::predict(const VectorXd& x) const {
  check_point(x, dims());
  const bool shifted = options_.tail != Tail::none;
  VectorXd phi(size());
  for (int i = 0; i < size(); ++i)
    phi[i] = detail::kernel_value(options_.basis, (centers_.row(i).transpose() - x).norm(), width_, shifted);
  VectorXd out = alpha_.transpose() * phi;
  if (beta_.rows() > 0) out += beta_.row(0).transpose();
  if (beta_.rows() > 1) out += beta_.bottomRows(dims()).transpose() * x;
  return out;
}

MatrixXd RbfNetwork::predict_many(const MatrixXd& x) const {
  if (x.cols() != dims())
    throw std::invalid_argument("RBF predict: points have " + std::to_string(x.cols()) +
                                " columns, the "
                                "network has " +
                                std::to_string(dims()));
  const MatrixXd phi = detail::kernel_from_squared_distances(options_.basis, detail::squared_distances(x, centers_),
                                                             width_, options_.tail != Tail::none);
  MatrixXd out = phi * alpha_;
  if (beta_.rows() > 0) out += detail::tail_matrix(options_.tail, x) * beta_;
  return out;
}

MatrixXd RbfNetwork::gradient(const VectorXd& x) const {
  check_point(x, dims());
  // d/dx phi(|x - c_i|) = psi(r_i) (x - c_i), psi = phi'(r)/r.
  MatrixXd weighted(size(), dims());
  for (int i = 0; i < size(); ++i) {
    const VectorXd diff = x - centers_.row(i).transpose();
    weighted.row(i) = basis_derivative_over_r(options_.basis, diff.norm(), width_) * diff.transpose();
  }
  MatrixXd g = alpha_.transpose() * weighted;
  if (beta_.rows() > 1) g += beta_.bottomRows(dims()).transpose();
  return g;
}

double RbfNetwork::predict_output(const VectorXd& x, int output, VectorXd* grad) const {
  check_point(x, dims());
  if (output < 0 || output >= outputs())
    throw std::invalid_argument("RBF predict: output index " + std::to_string(output) + " out of range");
  double value = 0.0;
  const bool shifted = options_.tail != Tail::none;
  if (grad) grad->setZero(dims());
  for (int i = 0; i < size(); ++i) {
    const VectorXd diff = x - centers_.row(i).transpose();
    const double r = diff.norm(), a = alpha_(i, output);
    value += a * detail::kernel_value(options_.basis, r, width_, shifted);
    if (grad) *grad += a * basis_derivative_over_r(options_.basis, r, width_) * diff;
  }
  if (beta_.rows() > 0) value += beta_(0, output);
  if (beta_.rows() > 1) {
    value += beta_.col(output).tail(dims()).dot(x);
    if (grad) *grad += beta_.col(output).tail(dims());
  }
  return value;
}

VectorXd RbfNetwork::loo_rms() const {
  return (loo_residuals_.colwise().squaredNorm() / static_cast<double>(size())).cwiseSqrt().transpose();
}

double rbf_criterion(const MatrixXd& points, const MatrixXd& values, const RbfOptions& options, double width,
                     double smoothing) {
  const Prepared prepared = detail::prepare(points, values, options);
  return detail::criterion(prepared, detail::spectrum(prepared, width), smoothing);
}

}  // namespace demfit::rbf_surrogate
