#include "study_support.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "demfit/identify/experiments.hpp"
#include "demfit/identify/units.hpp"

namespace demfit::identify::detail {

rbf_surrogate::Variable rbf_variable(const VariableSpec& v) { return {v.name, v.lower, v.upper, v.log_scale}; }

std::vector<rbf_surrogate::Variable> rbf_variables(const StudySpec& spec) {
  std::vector<rbf_surrogate::Variable> out;
  for (const auto& v : spec.variables) out.push_back(rbf_variable(v));
  return out;
}

Eigen::VectorXd initial_values(const StudySpec& spec) {
  Eigen::VectorXd x(spec.variables.size());
  for (std::size_t j = 0; j < spec.variables.size(); ++j) x(j) = spec.variables[j].initial;
  return x;
}

rbf_surrogate::Box initial_region(const StudySpec& spec, const std::vector<rbf_surrogate::Variable>& variables) {
  const Eigen::VectorXd center = rbf_surrogate::to_unit(variables, initial_values(spec));
  rbf_surrogate::Box box{center, center};
  for (std::size_t j = 0; j < spec.variables.size(); ++j) {
    const double width = spec.variables[j].initial_range;
    const double lower = std::clamp(center(j) - 0.5 * width, 0.0, 1.0 - width);
    box.lower(j) = lower;
    box.upper(j) = std::min(1.0, lower + width);
  }
  return box;
}

ParameterSet variable_values(const StudySpec& spec, const std::vector<rbf_surrogate::Variable>& variables,
                             const Eigen::VectorXd& unit) {
  const Eigen::VectorXd physical = rbf_surrogate::from_unit(variables, unit);
  ParameterSet out;
  for (std::size_t j = 0; j < spec.variables.size(); ++j) out[spec.variables[j].name] = physical(j);
  return out;
}

ParameterSet model_parameters(const StudySpec& spec, const Model& model,
                              const std::vector<rbf_surrogate::Variable>& variables, const Eigen::VectorXd& unit) {
  ParameterSet parameters = model.default_parameters();
  for (const auto& [name, value] : spec.fixed_parameters) parameters[name] = value;
  for (const auto& [name, value] : variable_values(spec, variables, unit)) parameters[name] = value;
  return parameters;
}

Eigen::VectorXd unit_per_physical(const StudySpec& spec, const std::vector<rbf_surrogate::Variable>& variables,
                                  const Eigen::VectorXd& unit) {
  const Eigen::VectorXd physical = rbf_surrogate::from_unit(variables, unit);
  Eigen::VectorXd out(spec.variables.size());
  for (std::size_t j = 0; j < spec.variables.size(); ++j) {
    const auto& v = spec.variables[j];
    out(j) = v.log_scale ? 1.0 / (physical(j) * std::log(v.upper / v.lower)) : 1.0 / (v.upper - v.lower);
  }
  return out;
}

void check_parameter_names(const StudySpec& spec, const Model& model) {
  const auto names = model.parameter_names();
  std::string known;
  for (const auto& n : names) known += (known.empty() ? "" : " ") + n;
  auto known_name = [&](const std::string& name) { return std::find(names.begin(), names.end(), name) != names.end(); };
  const std::string model_name =
      spec.experiments.empty() ? "model '" + spec.model_reference + "'" : std::string("any experiment's model");
  for (std::size_t j = 0; j < spec.variables.size(); ++j)
    if (!known_name(spec.variables[j].name))
      throw std::runtime_error("study: variables[" + std::to_string(j) + "].name: '" + spec.variables[j].name +
                               "' is not a parameter of " + model_name + "; known: " + known);
  for (const auto& [name, value] : spec.fixed_parameters)
    if (!known_name(name))
      throw std::runtime_error("study: model.fixed_parameters." + name + ": not a parameter of model '" +
                               spec.model_reference + "'; known: " + known);
  check_parameter_bounds(spec, model);
}

namespace {

// Relative mismatch allowed between a photo's frame and the model's picture: a frame measured to
// a few pixels (0.2 mm of 84 mm per pixel in the GranuDrum photos) passes; a unit slip or
// another drum does not.
constexpr double kPictureSpanTolerance = 0.02;

// A photo target's frame against the model's picture of the same curve: a photo read as 84 m
// across (image_diameter in mm by mistake) or of another drum would be compared in other
// millimetres than the model's, a unit error no objective value reveals.
void check_picture_span(const TargetSpec& t, const CurveDescriptor& curve, const std::string& field) {
  if (!t.image || !(curve.picture_span > 0.0)) return;
  const double photo = t.image->diameter;
  if (std::abs(photo / curve.picture_span - 1.0) <= kPictureSpanTolerance) return;
  char photo_text[32], model_text[32];
  std::snprintf(photo_text, sizeof photo_text, "%g", photo);
  std::snprintf(model_text, sizeof model_text, "%g", curve.picture_span);
  throw std::runtime_error(field + ".image_diameter ('" + t.name + "'): the photo is read as " + photo_text +
                           " m across, but the model's picture of '" + t.curve + "' spans " + model_text +
                           " m (its drum's inner diameter); give the inner diameter of the simulated drum in metres "
                           "(e.g. 0.084 for 84 mm)");
}

}  // namespace

void check_declared_curves(const StudySpec& spec, const Model& model) {
  const std::vector<CurveDescriptor> declared = model.curves();
  if (declared.empty()) return;
  for (std::size_t i = 0; i < spec.targets.size(); ++i) {
    const TargetSpec& t = spec.targets[i];
    const std::string field = "study: targets[" + std::to_string(i) + "]";
    const auto found =
        std::find_if(declared.begin(), declared.end(), [&](const CurveDescriptor& c) { return c.name == t.curve; });
    if (found == declared.end()) {
      std::vector<std::string> names;
      for (const auto& c : declared) names.push_back(c.name);
      std::sort(names.begin(), names.end());
      std::string known;
      for (const auto& n : names) known += (known.empty() ? "" : ", ") + n;
      // The same words as the initial-point check (study_preflight.cpp), now before any run.
      throw std::runtime_error(field + ".curve: '" + t.curve + "' is not a curve of model '" + spec.model_reference +
                               "'; it produces: " + known);
    }
    // unit_factor throws, naming the column, when the target's unit cannot convert to the curve's.
    unit_factor(t.data.x_label, found->x_label, field + ".x_column");
    unit_factor(t.data.y_label, found->y_label, field + ".y_column");
    check_picture_span(t, *found, field);
  }
}

void check_parameter_bounds(const StudySpec& spec, const Model& model) {
  const std::vector<ParameterDescriptor> descriptors = model.parameters();
  auto unit_of = [](const ParameterDescriptor& d) { return d.unit.empty() ? std::string() : " [" + d.unit + "]"; };
  for (std::size_t j = 0; j < spec.variables.size(); ++j) {
    const auto& v = spec.variables[j];
    const ParameterDescriptor* d = find_descriptor(descriptors, v.name);
    if (!d || d->valid.contains_interval(v.lower, v.upper)) continue;
    char bounds[96];
    std::snprintf(bounds, sizeof bounds, "[%g, %g]", v.lower, v.upper);
    throw std::runtime_error("study: variables[" + std::to_string(j) + "] '" + v.name + "': bounds " + bounds +
                             " leave the model's valid range " + d->valid.to_string() + unit_of(*d) +
                             "; move the bounds inside it");
  }
  for (const auto& [name, value] : spec.fixed_parameters) {
    const ParameterDescriptor* d = find_descriptor(descriptors, name);
    if (!d || d->valid.contains(value)) continue;
    char text[48];
    std::snprintf(text, sizeof text, "%g", value);
    throw std::runtime_error("study: model.fixed_parameters." + name + " = " + text +
                             " lies outside the model's valid range " + d->valid.to_string() + unit_of(*d) +
                             "; change it");
  }
}

std::vector<std::string> experiment_names(const StudySpec& spec) {
  std::vector<std::string> names;
  for (const auto& e : spec.experiments) names.push_back(e.name);
  if (names.empty()) names.push_back("");
  return names;
}

void check_experiments(const StudySpec& spec, const Model& model) {
  const auto* set = as_experiment_set(model);
  if (spec.experiments.empty()) {
    if (set) throw std::runtime_error("study: a single-model study was given a model of several experiments");
    return;
  }
  if (!set || set->size() != spec.experiments.size())
    throw std::runtime_error("study: experiments: the study lists " + std::to_string(spec.experiments.size()) +
                             " experiments; build its model with one model per experiment (ExperimentSetModel)");
  for (std::size_t e = 0; e < spec.experiments.size(); ++e) {
    const auto& experiment = spec.experiments[e];
    if (set->name(e) != experiment.name)
      throw std::runtime_error("study: experiments[" + std::to_string(e) + "]: model built for experiment '" +
                               set->name(e) + "', the study names '" + experiment.name + "'");
    const auto names = set->model(e).parameter_names();
    const auto descriptors = set->model(e).parameters();
    for (const auto& [name, value] : experiment.fixed_parameters) {
      const std::string field = "study: experiments[" + std::to_string(e) + "].model.fixed_parameters." + name;
      if (std::find(names.begin(), names.end(), name) == names.end())
        throw std::runtime_error(field + ": not a parameter of case '" + experiment.model_reference + "'");
      const ParameterDescriptor* d = find_descriptor(descriptors, name);
      if (d && !d->valid.contains(value)) {
        char text[48];
        std::snprintf(text, sizeof text, "%g", value);
        throw std::runtime_error(field + " = " + text + " lies outside the valid range " + d->valid.to_string() +
                                 "; change it");
      }
    }
  }
}

std::uint64_t iteration_seed(std::uint64_t study_seed, int iteration) {
  // splitmix64 of (seed, iteration): independent, reproducible streams per iteration.
  std::uint64_t z = study_seed + 0x9E3779B97F4A7C15ull * static_cast<std::uint64_t>(iteration + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

rbf_surrogate::MinimizeResult minimize_prediction(const ResponseSurrogate& surrogate,
                                                  const CompositeObjective& objective, const rbf_surrogate::Box& region,
                                                  std::uint64_t seed, std::optional<HeldCoordinate> held) {
  const int dims = static_cast<int>(region.dims());
  const int skipped = held ? held->index : dims;  // no coordinate skipped without `held`
  rbf_surrogate::Box free_region = rbf_surrogate::Box::unit(held ? dims - 1 : dims);
  for (int j = 0, k = 0; j < dims; ++j)
    if (j != skipped) {
      free_region.lower(k) = region.lower(j);
      free_region.upper(k++) = region.upper(j);
    }
  const auto full = [&](const Eigen::VectorXd& free) {
    Eigen::VectorXd x(dims);
    for (int j = 0, k = 0; j < dims; ++j) x(j) = j == skipped ? held->unit_value : free(k++);
    return x;
  };
  const auto function = [&](const Eigen::VectorXd& free, Eigen::VectorXd* gradient) {
    const Eigen::VectorXd x = full(free);
    if (gradient) {
      const Eigen::VectorXd g = surrogate.objective_gradient(x, objective);
      gradient->resize(free.size());
      for (int j = 0, k = 0; j < dims; ++j)
        if (j != skipped) (*gradient)(k++) = g(j);
    }
    return surrogate.predicted_objective(x, objective);
  };
  rbf_surrogate::MinimizeOptions options;
  options.global_evaluations = 400 + 100 * static_cast<int>(free_region.dims());
  options.local_starts = 3;
  options.seed = seed;
  options.use_gradient = true;
  options.local_evaluations = 200;
  rbf_surrogate::MinimizeResult result = rbf_surrogate::minimize(function, free_region, options);
  result.x = full(result.x);
  return result;
}

bool same_point(const Eigen::VectorXd& a, const Eigen::VectorXd& b) { return (a - b).cwiseAbs().maxCoeff() < 1e-14; }

std::vector<int> nearest_distinct(const std::vector<Eigen::VectorXd>& points, const Eigen::VectorXd& center,
                                  const Eigen::VectorXd& width, int minimum, int maximum) {
  const Eigen::VectorXd w = width.cwiseMax(1e-12);
  std::vector<std::pair<double, int>> order;
  for (int i = 0; i < static_cast<int>(points.size()); ++i)
    order.push_back({((points[i] - center).array() / w.array()).abs().maxCoeff(), i});
  std::stable_sort(order.begin(), order.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<int> chosen;
  for (const auto& entry : order) {
    if (static_cast<int>(chosen.size()) >= maximum) break;
    if (entry.first > 1.0 + 1e-12 && static_cast<int>(chosen.size()) >= minimum) break;
    bool duplicate = false;  // a repeated point (e.g. the verification run) adds no information
    for (int c : chosen) duplicate = duplicate || same_point(points[c], points[entry.second]);
    if (!duplicate) chosen.push_back(entry.second);
  }
  std::sort(chosen.begin(), chosen.end());  // run order: deterministic
  return chosen;
}

std::vector<double> to_std(const Eigen::VectorXd& v) { return std::vector<double>(v.data(), v.data() + v.size()); }

std::string format_number(double value) {
  if (!std::isfinite(value)) return "nan";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", value);
  return buffer;
}

std::string format_duration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "?";
  const long total = std::lround(seconds);
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, "%ldh%02ldm%02lds", total / 3600, (total / 60) % 60, total % 60);
  return buffer;
}

}  // namespace demfit::identify::detail

namespace demfit::identify::detail {

nlohmann::json uncertainty_json(const StudySpec& spec, const UncertaintyEstimate& estimate) {
  // JSON has no infinity: an unbounded interval is written as null.
  auto finite_or_null = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); };
  nlohmann::json json = {{"confidence", 0.95},
                         {"residual_variance", estimate.residual_variance},
                         {"degrees_of_freedom", estimate.degrees_of_freedom},
                         {"condition_number", finite_or_null(estimate.condition_number)},
                         {"jacobian", estimate.jacobian_source},
                         {"runs_used", estimate.runs_used},
                         {"simulation_noise_variance", estimate.simulation_noise_variance}};
  if (!estimate.effect_significance.empty()) json["effect_significance"] = nlohmann::json::object();
  if (!estimate.least_squares_estimate.empty()) json["least_squares_estimate"] = nlohmann::json::object();
  json["variables"] = nlohmann::json::array();
  json["correlation"] = nlohmann::json::array();
  json["standard_error"] = nlohmann::json::object();
  json["ci_half_width"] = nlohmann::json::object();
  json["unidentifiable"] = nlohmann::json::array();
  for (std::size_t j = 0; j < spec.variables.size(); ++j) {
    const std::string& name = spec.variables[j].name;
    json["variables"].push_back(name);
    json["standard_error"][name] = finite_or_null(estimate.standard_error[j]);
    json["ci_half_width"][name] = finite_or_null(estimate.ci_half_width[j]);
    if (estimate.unidentifiable[j]) json["unidentifiable"].push_back(name);
    if (!estimate.effect_significance.empty())
      json["effect_significance"][name] = finite_or_null(estimate.effect_significance[j]);
    if (!estimate.least_squares_estimate.empty())
      json["least_squares_estimate"][name] = finite_or_null(estimate.least_squares_estimate[j]);
    nlohmann::json row = nlohmann::json::array();
    for (std::size_t i = 0; i < spec.variables.size(); ++i) row.push_back(finite_or_null(estimate.correlation(j, i)));
    json["correlation"].push_back(row);
  }
  return json;
}

}  // namespace demfit::identify::detail
