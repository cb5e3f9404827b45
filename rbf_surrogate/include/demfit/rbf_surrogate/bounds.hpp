#pragma once
// Design variables and the unit-cube normalisation used by every other part of rbf_surrogate
// (docs/spec.md section 3: "Variables normalised to [0, 1] (optionally log-scaled)").
#include <Eigen/Dense>
#include <string>
#include <vector>

namespace demfit::rbf_surrogate {

using Eigen::MatrixXd;
using Eigen::VectorXd;

// One design variable in physical units. With log_scale the unit coordinate is linear in
// log(value), which needs lower > 0 (stiffness-like parameters spanning decades).
struct Variable {
  std::string name;
  double lower = 0.0;
  double upper = 1.0;
  bool log_scale = false;
};

// Throws std::invalid_argument (one line naming the variable) when lower >= upper, a bound is not
// finite, or log_scale is set with lower <= 0.
void validate(const std::vector<Variable>& variables);

VectorXd to_unit(const std::vector<Variable>& variables, const VectorXd& physical);  // -> [0,1]^n
VectorXd from_unit(const std::vector<Variable>& variables, const VectorXd& unit);
// The same mapping for one variable (the vector forms apply it coordinate by coordinate).
double to_unit(const Variable& variable, double physical);
double from_unit(const Variable& variable, double unit);

// Axis-aligned box, in unit coordinates everywhere in this library.
struct Box {
  VectorXd lower, upper;
  static Box unit(int dims);  // [0,1]^dims
  int dims() const { return static_cast<int>(lower.size()); }
  VectorXd width() const { return upper - lower; }
  VectorXd center() const { return 0.5 * (lower + upper); }
  bool contains(const VectorXd& x, double tolerance = 0.0) const;
  VectorXd clamp(const VectorXd& x) const;       // nearest point of the box
  VectorXd to_local(const VectorXd& x) const;    // box -> [0,1]^n
  VectorXd from_local(const VectorXd& u) const;  // [0,1]^n -> box
};

// Throws std::invalid_argument when sizes differ, lower > upper or a bound is not finite.
void validate(const Box& box);

}  // namespace demfit::rbf_surrogate
