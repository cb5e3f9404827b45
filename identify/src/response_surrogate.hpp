#pragma once
// Internal: RBF networks over the response vectors of the runs (one output per curve value, or
// per principal-component score), fitted in the local coordinates of a "fit box" so that small
// late subregions stay well conditioned. The objective of a prediction is the composite
// objective of the predicted responses (docs/spec.md 3: the objective is computed from predicted curves).
#include <vector>

#include <Eigen/Dense>

#include "demfit/identify/objective.hpp"
#include "demfit/identify/study_spec.hpp"
#include "demfit/rbf_surrogate/bounds.hpp"
#include "demfit/rbf_surrogate/rbf_network.hpp"

namespace demfit::identify::detail {

class ResponseSurrogate {
 public:
  // points: rows in unit coordinates; responses: rows = runs. Points outside fit_box are allowed.
  ResponseSurrogate(const Eigen::MatrixXd& points, const Eigen::MatrixXd& responses, const rbf_surrogate::Box& fit_box,
                    const StudySpec& spec);
  Eigen::VectorXd predict(const Eigen::VectorXd& unit_x) const;  // response vector
  double predicted_objective(const Eigen::VectorXd& unit_x, const CompositeObjective& objective) const;
  // Gradient of the predicted objective (central differences in local coordinates).
  Eigen::VectorXd objective_gradient(const Eigen::VectorXd& unit_x, const CompositeObjective& objective) const;
  int components() const { return static_cast<int>(basis_.cols()); }
  double mean_loo_rms() const;

 private:
  rbf_surrogate::Box fit_box_;
  rbf_surrogate::RbfNetwork network_;
  bool principal_components_ = false;
  Eigen::VectorXd mean_;
  Eigen::MatrixXd basis_;  // m x k (principal directions) when principal_components_
};

rbf_surrogate::RbfOptions rbf_options(const StudySpec& spec);

}  // namespace demfit::identify::detail
