// Unit-cube normalisation (docs/spec.md section 3) and box helpers.
#include "demfit/rbf_surrogate/bounds.hpp"

#include <cmath>
#include <stdexcept>

namespace demfit::rbf_surrogate {

void validate(const std::vector<Variable>& variables) {
  for (const auto& v : variables) {
    if (!std::isfinite(v.lower) || !std::isfinite(v.upper))
      throw std::invalid_argument("variable '" + v.name + "': bounds must be finite numbers");
    if (!(v.lower < v.upper))
      throw std::invalid_argument("variable '" + v.name + "': lower bound must be below upper bound");
    if (v.log_scale && v.lower <= 0.0)
      throw std::invalid_argument("variable '" + v.name + "': log_scale needs a positive lower bound");
  }
}

static void check_size(const std::vector<Variable>& variables, const VectorXd& x) {
  if (static_cast<std::size_t>(x.size()) != variables.size())
    throw std::invalid_argument("point has " + std::to_string(x.size()) + " coordinates but there are " +
                                std::to_string(variables.size()) + " variables");
}

double to_unit(const Variable& v, double physical) {
  if (v.log_scale) return std::log(physical / v.lower) / std::log(v.upper / v.lower);
  return (physical - v.lower) / (v.upper - v.lower);
}

double from_unit(const Variable& v, double unit) {
  if (v.log_scale) return v.lower * std::exp(unit * std::log(v.upper / v.lower));
  return v.lower + unit * (v.upper - v.lower);
}

VectorXd to_unit(const std::vector<Variable>& variables, const VectorXd& physical) {
  check_size(variables, physical);
  VectorXd u(physical.size());
  for (std::size_t i = 0; i < variables.size(); ++i)
    u[static_cast<Eigen::Index>(i)] = to_unit(variables[i], physical[static_cast<Eigen::Index>(i)]);
  return u;
}

VectorXd from_unit(const std::vector<Variable>& variables, const VectorXd& unit) {
  check_size(variables, unit);
  VectorXd x(unit.size());
  for (std::size_t i = 0; i < variables.size(); ++i)
    x[static_cast<Eigen::Index>(i)] = from_unit(variables[i], unit[static_cast<Eigen::Index>(i)]);
  return x;
}

Box Box::unit(int dims) { return Box{VectorXd::Zero(dims), VectorXd::Ones(dims)}; }

bool Box::contains(const VectorXd& x, double tolerance) const {
  return x.size() == lower.size() && (x.array() >= lower.array() - tolerance).all() &&
         (x.array() <= upper.array() + tolerance).all();
}

VectorXd Box::clamp(const VectorXd& x) const { return x.cwiseMax(lower).cwiseMin(upper); }

VectorXd Box::to_local(const VectorXd& x) const { return (x - lower).cwiseQuotient(width()); }

VectorXd Box::from_local(const VectorXd& u) const { return lower + u.cwiseProduct(width()); }

void validate(const Box& box) {
  if (box.lower.size() != box.upper.size()) throw std::invalid_argument("box: lower and upper have different sizes");
  if (!box.lower.allFinite() || !box.upper.allFinite())
    throw std::invalid_argument("box: bounds must be finite numbers");
  if ((box.lower.array() > box.upper.array()).any())
    throw std::invalid_argument("box: a lower bound is above its upper bound");
}

}  // namespace demfit::rbf_surrogate
