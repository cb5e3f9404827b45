#pragma once
// Kriging (Gaussian-process) model with an anisotropic Matérn-5/2 radial kernel and a constant mean,
// hyperparameters by maximum likelihood. It is the RBF network of rbf_network.hpp with one width per
// coordinate plus a predictive standard deviation (the "power function" of the kernel matrix), which
// expected-improvement infill needs (Jones, Schonlau & Welch 1998, "Efficient global optimization").
//   k(x, x') = σ² m(r),  r² = Σ_j (x_j − x'_j)² / ℓ_j²,  m(r) = (1 + √5 r + 5r²/3) e^{−√5 r}
//   K = σ²(R + g I):  μ̂ = 1ᵀK⁻¹y / 1ᵀK⁻¹1,  σ̂² = (y − μ̂)ᵀ(R+gI)⁻¹(y − μ̂)/n   (concentrated out)
//   −log L(ℓ, g) = n/2 log σ̂² + ½ log|R + gI|   minimised over log ℓ (and log g when noisy).
// Prediction (universal-kriging variance: the constant mean is estimated too):
//   m(x) = μ̂ + rᵀ(R+gI)⁻¹(y − μ̂),
//   s²(x) = σ̂² [1 − rᵀ(R+gI)⁻¹r + (1 − 1ᵀ(R+gI)⁻¹r)² / 1ᵀ(R+gI)⁻¹1]   (latent f, nugget excluded).
#include "demfit/rbf_surrogate/bounds.hpp"

#include <cmath>
#include <memory>

namespace demfit::rbf_surrogate {

class KrigingModel;

// A known part of the response that the kriging model corrects (a cheaper level's model in the
// autoregressive multi-fidelity form, multi_fidelity.hpp): y(x) = scale · m_base(x) + Z(x). The
// model is fitted to y_i − scale · m_base(x_i); its mean adds scale · m_base(x) (and its gradient),
// its variance scale² s_base²(x). No base: no trend.
struct KrigingTrend {
  std::shared_ptr<const KrigingModel> base;
  double scale = 1.0;
};

// Correlation m(r) of the scaled distance: Matérn-5/2 (twice differentiable sample paths) or
// Gaussian e^{−r²/2} (infinitely smooth; the DACE default, Sacks et al. 1989).
enum class KrigingKernel { matern52, gaussian };

struct KrigingOptions {
  KrigingKernel kernel = KrigingKernel::matern52;
  // Estimate a nugget g (noise variance / process variance) by maximum likelihood, for noisy
  // values; otherwise g = min_nugget (a jitter that keeps R + gI positive definite).
  bool estimate_noise = false;
  double min_nugget = 1e-10;
  double max_nugget = 0.3;
  double min_length = 0.01;  // length-scale bounds in the (unit-cube) coordinates of the points
  double max_length = 20.0;
  // Warm start for the likelihood search (e.g. the previous fit's length scales and nugget):
  // the search then starts there as well as from the default start (all ℓ = 0.3). Empty / 0: none.
  VectorXd length_hint;
  double nugget_hint = 0.0;
  int likelihood_evaluations = 0;  // BOBYQA budget per start; 0: 40·(parameters + 1)
  // Skip the likelihood search and use exactly these hyperparameters (length_hint required).
  bool fixed_hyperparameters = false;
  KrigingTrend trend;  // a cheaper level's model this one corrects (none by default)
};

class KrigingModel {
 public:
  // points n×d (rows), values n. Throws std::invalid_argument (one line) on NaN/inf, size mismatch
  // or fewer than 2 points.
  static KrigingModel fit(const MatrixXd& points, const VectorXd& values, const KrigingOptions& options = {});

  double mean(const VectorXd& x, VectorXd* gradient = nullptr) const;  // predicted value (and ∇)
  VectorXd means(const MatrixXd& points) const;                        // mean at each row
  double standard_deviation(const VectorXd& x) const;                  // of the latent function
  void predict(const VectorXd& x, double& mean, double& standard_deviation) const;

  const VectorXd& length_scales() const { return length_; }
  KrigingKernel kernel() const { return kernel_; }
  const KrigingTrend& trend() const { return trend_; }
  double nugget() const { return nugget_; }  // relative to the process variance
  double process_variance() const { return sigma2_ * y_scale_ * y_scale_; }
  // Concentrated −log L of the values as given (normalisation Jacobian n·log(scale) included,
  // constant n/2·(1 + log 2π) left out): comparable between fits of transformed values once the
  // transform's own Jacobian is added.
  double data_negative_log_likelihood() const { return nll_ + static_cast<double>(size()) * std::log(y_scale_); }
  int size() const { return static_cast<int>(x_.rows()); }
  int dims() const { return static_cast<int>(x_.cols()); }

 private:
  VectorXd correlations(const VectorXd& x) const;  // r_i = m(|x − x_i|_ℓ)

  MatrixXd x_;
  KrigingKernel kernel_ = KrigingKernel::matern52;
  KrigingTrend trend_;
  VectorXd length_;
  double nugget_ = 0.0;
  double mu_ = 0.0, sigma2_ = 1.0, nll_ = 0.0;  // in normalised units
  double y_shift_ = 0.0, y_scale_ = 1.0;        // y_normalised = (y − shift) / scale
  Eigen::MatrixXd lower_;                       // Cholesky factor L of R + gI
  VectorXd weights_;                            // (R+gI)⁻¹(y − μ̂)
  VectorXd inverse_ones_;                       // (R+gI)⁻¹1
  double ones_inverse_ones_ = 1.0;              // 1ᵀ(R+gI)⁻¹1
};

// Matérn-5/2 correlation m(r) and m'(r)/r (finite at r = 0), exposed for tests.
double matern52(double r);
double matern52_derivative_over_r(double r);
double correlation(KrigingKernel kernel, double r);
double correlation_derivative_over_r(KrigingKernel kernel, double r);

}  // namespace demfit::rbf_surrogate
