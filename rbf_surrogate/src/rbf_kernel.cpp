// Radial basis functions phi(r), psi(r) = phi'(r)/r and the polynomial tail.
#include "rbf_internal.hpp"

#include <cmath>

namespace demfit::rbf_surrogate {

double basis_value(Basis basis, double r, double width) {
  switch (basis) {
    case Basis::multiquadric:
      return std::sqrt(r * r + width * width);
    case Basis::gaussian:
      return std::exp(-(r * r) / (width * width));
    case Basis::inverse_multiquadric:
      return 1.0 / std::sqrt(r * r + width * width);
    case Basis::cubic:
      return r * r * r;
    case Basis::thin_plate:
      return r > 0.0 ? r * r * std::log(r) : 0.0;
  }
  return 0.0;
}

double basis_derivative_over_r(Basis basis, double r, double width) {
  // The gradient of phi(|x - c|) is psi(r)·(x - c); psi stays finite at r = 0 except for the thin
  // plate spline, whose (x - c) factor vanishes faster (r log r -> 0), so 0 is returned there.
  switch (basis) {
    case Basis::multiquadric:
      return 1.0 / std::sqrt(r * r + width * width);
    case Basis::gaussian:
      return -2.0 / (width * width) * std::exp(-(r * r) / (width * width));
    case Basis::inverse_multiquadric: {
      const double s = r * r + width * width;
      return -1.0 / (s * std::sqrt(s));
    }
    case Basis::cubic:
      return 3.0 * r;
    case Basis::thin_plate:
      return r > 0.0 ? 2.0 * std::log(r) + 1.0 : 0.0;
  }
  return 0.0;
}

namespace detail {

int tail_terms(Tail tail, int dims) {
  switch (tail) {
    case Tail::none:
      return 0;
    case Tail::constant:
      return 1;
    case Tail::linear:
      return dims + 1;
  }
  return 0;
}

MatrixXd tail_matrix(Tail tail, const MatrixXd& x) {
  const int q = tail_terms(tail, static_cast<int>(x.cols()));
  MatrixXd p(x.rows(), q);
  if (q > 0) p.col(0).setOnes();
  if (q > 1) p.rightCols(x.cols()) = x;
  return p;
}

MatrixXd squared_distances(const MatrixXd& a, const MatrixXd& b) {
  MatrixXd d2(a.rows(), b.rows());
  for (Eigen::Index j = 0; j < b.rows(); ++j)
    for (Eigen::Index i = 0; i < a.rows(); ++i) d2(i, j) = (a.row(i) - b.row(j)).squaredNorm();
  return d2;
}

double kernel_value(Basis basis, double r, double width, bool shifted) {
  if (!shifted) return basis_value(basis, r, width);
  const double r2 = r * r;
  switch (basis) {
    case Basis::multiquadric:
      return r2 / (std::sqrt(r2 + width * width) + width);
    case Basis::gaussian:
      return std::expm1(-r2 / (width * width));
    case Basis::inverse_multiquadric: {
      const double s = std::sqrt(r2 + width * width);
      return -r2 / (width * s * (s + width));
    }
    case Basis::cubic:
    case Basis::thin_plate:
      return basis_value(basis, r, width);
  }
  return 0.0;
}

MatrixXd kernel_from_squared_distances(Basis basis, const MatrixXd& d2, double width, bool shifted) {
  return d2.unaryExpr([&](double v) { return kernel_value(basis, std::sqrt(v), width, shifted); });
}

double definiteness_sign(Basis basis) { return basis == Basis::multiquadric ? -1.0 : 1.0; }

bool uses_width(Basis basis) { return basis != Basis::cubic && basis != Basis::thin_plate; }

const char* basis_name(Basis basis) {
  switch (basis) {
    case Basis::multiquadric:
      return "multiquadric";
    case Basis::gaussian:
      return "gaussian";
    case Basis::inverse_multiquadric:
      return "inverse_multiquadric";
    case Basis::cubic:
      return "cubic";
    case Basis::thin_plate:
      return "thin_plate";
  }
  return "?";
}

}  // namespace detail
}  // namespace demfit::rbf_surrogate
