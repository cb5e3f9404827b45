#pragma once
// Internal helpers of the study loop: variable mapping between study, model and unit cube,
// seeds, the predicted-objective minimisation, and text formatting for progress lines.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <nlohmann/json.hpp>

#include "demfit/identify/model.hpp"
#include "demfit/identify/objective.hpp"
#include "demfit/identify/study_spec.hpp"
#include "demfit/identify/uncertainty.hpp"
#include "demfit/rbf_surrogate/bounds.hpp"
#include "demfit/rbf_surrogate/optimize.hpp"
#include "response_surrogate.hpp"

namespace demfit::identify::detail {

rbf_surrogate::Variable rbf_variable(const VariableSpec& variable);  // the unit-cube mapping's view of it
std::vector<rbf_surrogate::Variable> rbf_variables(const StudySpec& spec);
Eigen::VectorXd initial_values(const StudySpec& spec);  // physical
// Iteration-0 region: initial_range around the initial point, shifted to stay in [0, 1].
rbf_surrogate::Box initial_region(const StudySpec& spec, const std::vector<rbf_surrogate::Variable>& variables);
// Everything the model receives: its defaults, the study's fixed values, the variables at `unit`.
ParameterSet model_parameters(const StudySpec& spec, const Model& model,
                              const std::vector<rbf_surrogate::Variable>& variables, const Eigen::VectorXd& unit);
ParameterSet variable_values(const StudySpec& spec, const std::vector<rbf_surrogate::Variable>& variables,
                             const Eigen::VectorXd& unit);
// d(unit coordinate)/d(physical value) of each variable at `unit`.
Eigen::VectorXd unit_per_physical(const StudySpec& spec, const std::vector<rbf_surrogate::Variable>& variables,
                                  const Eigen::VectorXd& unit);
// Throws "study: variables[i].name: 'x' is not a parameter of model ..." for unknown names
// (with several experiments: of no experiment's model).
void check_parameter_names(const StudySpec& spec, const Model& model);
// Every target names a curve the model declares (Model::curves), with units that convert to the
// curve's; nothing to check when the model declares none.
void check_declared_curves(const StudySpec& spec, const Model& model);
// Throws (one line naming the variable, its bounds and the valid range) when a variable's bounds
// or a fixed value leave the valid range of the model's parameter descriptors. Called by
// check_parameter_names, so before any store exists.
void check_parameter_bounds(const StudySpec& spec, const Model& model);
// A study with experiments needs an ExperimentSetModel built for it (same experiment names) and
// each experiment's fixed_parameters must be parameters of its model; a single-model study needs
// a plain model. Throws one line naming the field.
void check_experiments(const StudySpec& spec, const Model& model);
// {""} in the single-model form, else the experiment names in order.
std::vector<std::string> experiment_names(const StudySpec& spec);
std::uint64_t iteration_seed(std::uint64_t study_seed, int iteration);
// One coordinate held at a value while the others are minimised (a profile of the prediction).
struct HeldCoordinate {
  int index = 0;
  double unit_value = 0.0;
};
// The predicted composite objective's minimum over `region` (global search, then gradient-based
// local starts). With `held`, over the other coordinates only; the result's x is the full point.
rbf_surrogate::MinimizeResult minimize_prediction(const ResponseSurrogate& surrogate,
                                                  const CompositeObjective& objective, const rbf_surrogate::Box& region,
                                                  std::uint64_t seed, std::optional<HeldCoordinate> held = {});

// Two points in unit coordinates are the same run if they agree to 1e-14 in every variable: a
// deterministic model answers both alike, so a repeat adds no information (fits, infill, design).
bool same_point(const Eigen::VectorXd& a, const Eigen::VectorXd& b);

// Indices (ascending) of the distinct points (repeated points count once) within one `width` of
// `center` (distance max_j |x_j - c_j| / width_j <= 1), nearest first, topped up with the next
// nearest to `minimum` and cut at `maximum`: the runs a surrogate is fitted to, and the
// uncertainty regression's sample.
std::vector<int> nearest_distinct(const std::vector<Eigen::VectorXd>& points, const Eigen::VectorXd& center,
                                  const Eigen::VectorXd& width, int minimum, int maximum);

std::vector<double> to_std(const Eigen::VectorXd& v);
std::string format_number(double value);      // "%.6g", "nan" for NaN
std::string format_duration(double seconds);  // "1h02m03s"

}  // namespace demfit::identify::detail

namespace demfit::identify::detail {
// The uncertainty estimate as stored in the result JSON (by variable name).
nlohmann::json uncertainty_json(const StudySpec& spec, const UncertaintyEstimate& estimate);
}  // namespace demfit::identify::detail
