#pragma once
// Radial-basis-function network with many outputs sharing one factorisation (docs/spec.md section 3).
//   f_j(x) = sum_i alpha_ij phi(|x - x_i|) + sum_k beta_kj p_k(x),   sum_i alpha_ij p_k(x_i) = 0
// Width (and optional ridge smoothing) chosen by the closed-form leave-one-out error of Rippa (1999),
// e_ij = alpha_ij / (M^-1)_ii, or by GCV (diagonal replaced by its mean), summed over outputs with
// each output normalised by its variance.
#include "demfit/rbf_surrogate/bounds.hpp"

#include <optional>

namespace demfit::rbf_surrogate {

// phi(r) with width c: multiquadric sqrt(r^2+c^2) (Hardy), gaussian exp(-(r/c)^2),
// inverse_multiquadric 1/sqrt(r^2+c^2), cubic r^3 and thin_plate r^2 log r (no width).
enum class Basis { multiquadric, gaussian, inverse_multiquadric, cubic, thin_plate };
enum class Tail { none, constant, linear };  // polynomial tail; cubic/thin_plate need linear
enum class WidthCriterion { loo, gcv };

struct RbfOptions {
  Basis basis = Basis::multiquadric;
  Tail tail = Tail::linear;
  WidthCriterion criterion = WidthCriterion::loo;
  bool smoothing = false;                 // choose a ridge term by the same criterion (noisy data)
  std::optional<double> fixed_width;      // skip the width search
  std::optional<double> fixed_smoothing;  // ridge term relative to the kernel scale, skips search
  // Previous optimum width (e.g. last iteration's fit): the search is narrowed to [hint/8, 8·hint]
  // (9 grid + 10 golden steps instead of 16 + 10).
  std::optional<double> width_hint;
};

class RbfNetwork {
 public:
  // points n×d (rows, any coordinates; unit cube recommended), values n×m (one column per output).
  // Throws std::invalid_argument (one line) on NaN/inf, duplicate points, size mismatch, too few
  // points for the tail, points not affinely independent for a linear tail.
  static RbfNetwork fit(const MatrixXd& points, const MatrixXd& values, const RbfOptions& options = {});

  VectorXd predict(const VectorXd& x) const;       // m outputs
  MatrixXd predict_many(const MatrixXd& x) const;  // rows of x -> rows of outputs (k×m)
  MatrixXd gradient(const VectorXd& x) const;      // m×d, analytic
  // Value and gradient of one output (cheap path for a scalar objective model).
  double predict_output(const VectorXd& x, int output, VectorXd* gradient = nullptr) const;

  VectorXd loo_rms() const;  // per output, closed-form leave-one-out RMS error (PRESS/n)^½
  const MatrixXd& loo_residuals() const { return loo_residuals_; }  // n×m, y_i - f^{(-i)}(x_i)
  double criterion_value() const { return criterion_value_; }       // normalised criterion at optimum

  double width() const { return width_; }          // 0 for cubic / thin_plate
  double smoothing() const { return smoothing_; }  // absolute ridge added to the diagonal
  int outputs() const { return static_cast<int>(alpha_.cols()); }
  int dims() const { return static_cast<int>(centers_.cols()); }
  int size() const { return static_cast<int>(centers_.rows()); }
  const MatrixXd& centers() const { return centers_; }
  const RbfOptions& options() const { return options_; }

 private:
  MatrixXd centers_;        // n×d
  MatrixXd alpha_;          // n×m
  MatrixXd beta_;           // q×m (q = 0, 1 or d+1)
  MatrixXd loo_residuals_;  // n×m
  double width_ = 0.0;
  double smoothing_ = 0.0;
  double criterion_value_ = 0.0;
  RbfOptions options_;
};

// Kernel value phi(r) and psi(r) = phi'(r)/r (finite at r = 0 where the gradient needs it).
double basis_value(Basis basis, double r, double width);
double basis_derivative_over_r(Basis basis, double r, double width);

// Leave-one-out/GCV criterion for a given width and absolute smoothing: used by the width search
// and exposed so tests can scan it. Same normalisation as RbfNetwork::criterion_value().
double rbf_criterion(const MatrixXd& points, const MatrixXd& values, const RbfOptions& options, double width,
                     double smoothing);

}  // namespace demfit::rbf_surrogate
