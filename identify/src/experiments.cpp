// Several experiments in one study (see experiments.hpp).
#include "demfit/identify/experiments.hpp"

#include <algorithm>
#include <set>
#include <stdexcept>

namespace demfit::identify {

ExperimentSetModel::ExperimentSetModel(const StudySpec& spec, std::vector<std::unique_ptr<Model>> models) {
  if (spec.experiments.empty()) throw std::invalid_argument("ExperimentSetModel: the study has no \"experiments\"");
  if (models.size() != spec.experiments.size())
    throw std::invalid_argument("ExperimentSetModel: " + std::to_string(models.size()) + " models for " +
                                std::to_string(spec.experiments.size()) + " experiments");
  for (std::size_t e = 0; e < models.size(); ++e) {
    if (!models[e])
      throw std::invalid_argument("ExperimentSetModel: no model for experiment " + spec.experiments[e].name);
    Experiment experiment{spec.experiments[e].name, std::move(models[e]), spec.experiments[e].fixed_parameters, {}};
    experiment.accepted = experiment.model->parameter_names();
    experiments_.push_back(std::move(experiment));
  }
}

std::vector<ParameterDescriptor> ExperimentSetModel::parameters() const {
  std::vector<ParameterDescriptor> out;
  for (const auto& e : experiments_)
    for (const ParameterDescriptor& d : e.model->parameters()) {
      ParameterDescriptor* same = nullptr;
      for (auto& o : out)
        if (o.name == d.name) same = &o;
      if (!same) {
        out.push_back(d);
        continue;
      }
      ParameterRange& r = same->valid;
      if (d.valid.lower > r.lower || (d.valid.lower == r.lower && d.valid.lower_open)) {
        r.lower = d.valid.lower;
        r.lower_open = d.valid.lower_open;
      }
      if (d.valid.upper < r.upper || (d.valid.upper == r.upper && d.valid.upper_open)) {
        r.upper = d.valid.upper;
        r.upper_open = d.valid.upper_open;
      }
    }
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
  return out;
}

std::vector<CurveDescriptor> ExperimentSetModel::curves() const {
  std::vector<CurveDescriptor> out;
  for (const auto& e : experiments_) {
    const auto declared = e.model->curves();
    if (declared.empty()) return {};
    for (const CurveDescriptor& c : declared) out.push_back({e.name + "/" + c.name, c.x_label, c.y_label, c.picture_span});
  }
  return out;
}

ParameterSet ExperimentSetModel::experiment_parameters(std::size_t experiment, const ParameterSet& parameters) const {
  const Experiment& e = experiments_.at(experiment);
  ParameterSet out = e.model->default_parameters();
  for (const auto& [name, value] : e.fixed) out[name] = value;
  for (const auto& [name, value] : parameters)
    if (std::find(e.accepted.begin(), e.accepted.end(), name) != e.accepted.end()) out[name] = value;
  return out;
}

CurveSet ExperimentSetModel::evaluate(const ParameterSet& parameters, const EvaluationContext& context) const {
  std::vector<std::string> names;
  std::vector<EvaluationOutcome> outcomes;
  for (std::size_t e = 0; e < experiments_.size(); ++e) {
    names.push_back(experiments_[e].name);
    EvaluationOutcome outcome;
    try {
      outcome.curves = experiments_[e].model->evaluate(experiment_parameters(e, parameters), context);
      outcome.ok = true;
    } catch (const std::exception& error) {
      throw std::runtime_error("experiment '" + experiments_[e].name + "': " + error.what());
    }
    outcomes.push_back(std::move(outcome));
  }
  return combine_experiment_outcomes(names, std::move(outcomes)).curves;
}

const ExperimentSetModel* as_experiment_set(const Model& model) {
  return dynamic_cast<const ExperimentSetModel*>(&model);
}

std::vector<const Model*> experiment_models(const Model& model) {
  if (const auto* set = as_experiment_set(model)) {
    std::vector<const Model*> out;
    for (std::size_t e = 0; e < set->size(); ++e) out.push_back(&set->model(e));
    return out;
  }
  return {&model};
}

std::string experiment_curve_key(const std::string& experiment, const std::string& curve) {
  return experiment.empty() ? curve : experiment + "/" + curve;
}

EvaluationOutcome combine_experiment_outcomes(const std::vector<std::string>& names,
                                              std::vector<EvaluationOutcome> outcomes) {
  if (names.size() != outcomes.size()) throw std::invalid_argument("combine_experiment_outcomes: size mismatch");
  if (outcomes.size() == 1 && names[0].empty()) return std::move(outcomes[0]);
  EvaluationOutcome point;
  point.ok = true;
  for (std::size_t e = 0; e < outcomes.size(); ++e) {
    point.wall_seconds += outcomes[e].wall_seconds;
    if (!outcomes[e].ok) {
      if (point.ok) point.error = "experiment '" + names[e] + "': " + outcomes[e].error;
      point.ok = false;
      continue;
    }
    for (auto& [curve, values] : outcomes[e].curves)
      point.curves[experiment_curve_key(names[e], curve)] = std::move(values);
  }
  if (!point.ok) point.curves.clear();
  return point;
}

PointJobs::PointJobs(const Model& model, const std::vector<ParameterSet>& points) {
  const ExperimentSetModel* set = as_experiment_set(model);
  if (set)
    for (std::size_t e = 0; e < set->size(); ++e) names_.push_back(set->name(e));
  else
    names_.push_back("");
  for (const ParameterSet& parameters : points)
    for (std::size_t e = 0; e < names_.size(); ++e)
      jobs_.push_back({e, set ? set->experiment_parameters(e, parameters) : parameters});
  parts_.assign(points.size(), std::vector<EvaluationOutcome>(names_.size()));
  missing_.assign(points.size(), names_.size());
}

bool PointJobs::finish(std::size_t job, const EvaluationOutcome& part, std::size_t& point, EvaluationOutcome& outcome) {
  const std::size_t p = job / names_.size();
  parts_.at(p)[job % names_.size()] = part;
  if (--missing_[p] > 0) return false;
  point = p;
  outcome = combine_experiment_outcomes(names_, std::move(parts_[p]));
  return true;
}

}  // namespace demfit::identify
