// The model a diagnosis fits and its candidate effects (diagnosis_model.hpp).
#include "demfit/cases/diagnosis_model.hpp"

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "demfit/cases/case_spec.hpp"
#include "demfit/cases/effect_catalogue.hpp"
#include "demfit/cases/model_factory.hpp"
#include "demfit/cases/parameter_table.hpp"
#include "demfit/diagnose/analytic_effects_model.hpp"
#include "demfit/identify/experiments.hpp"
#include "demfit/identify/external_model.hpp"

namespace demfit::cases {
namespace {

// Whether a catalogue parameter exists under the case's contact law. The catalogue offers each law
// its own effects (cases/src/effect_catalogue.cpp); a case refuses every parameter of another law
// (cases/src/dem_setup.cpp with_parameters), so such an effect cannot be a candidate there.
bool exists_under_law(const CaseSpec& case_spec, const std::string& parameter) {
  const ParameterRow* row = find_parameter(parameter);
  return row && row->applies_to(case_spec.law);
}

// The cases catalogue (cases/effect_catalogue.hpp) as diagnose candidates: the effects that apply
// to a case. An effect is left out, with a note, when one of its parameters is a study variable
// or already differs from its off value in the model (`values`: the effect is then part of the
// base model, not a candidate). `experiment` non-empty: the effect's curves are qualified
// "<experiment>/<curve>" as an experiments study keys them.
std::vector<diagnose::EffectCandidate> dem_candidates(const CaseSpec& case_spec,
                                                      const identify::ParameterSet& values,
                                                      const std::vector<identify::VariableSpec>& variables,
                                                      const std::string& experiment) {
  std::vector<diagnose::EffectCandidate> out;
  for (const auto& effect : effects_for_case(case_spec)) {
    diagnose::EffectCandidate c{effect.name, effect.description, {}, effect.curves};
    if (!experiment.empty())
      for (auto& curve : c.curves) curve = experiment + "/" + curve;
    std::string reason;
    for (const auto& p : effect.parameters) {
      c.parameters.push_back(p);
      if (!exists_under_law(case_spec, p.name))
        reason = "'" + p.name + "' does not exist under the case's contact law " + to_string(case_spec.law);
      for (const auto& v : variables)
        if (v.name == p.name) reason = "'" + p.name + "' is a study variable";
      const auto found = values.find(p.name);
      if (reason.empty() && found != values.end() && found->second != p.off_value)
        reason = "the model already has " + p.name + " = " + std::to_string(found->second) +
                 " (off: " + std::to_string(p.off_value) + ")";
    }
    if (reason.empty()) {
      out.push_back(std::move(c));
    } else {
      std::fprintf(stderr, "demfit: note: effect '%s'%s is not a candidate: %s\n", effect.name.c_str(),
                   experiment.empty() ? "" : (" of experiment '" + experiment + "'").c_str(), reason.c_str());
    }
  }
  return out;
}

// The candidates an external study declares (model.external.candidates), as diagnose candidates.
// Left out with a note, as for the catalogue: a candidate whose parameter the study varies, or
// fixes at another value than its off value (the effect is then part of the base model).
std::vector<diagnose::EffectCandidate> external_candidates(const identify::StudySpec& spec) {
  const identify::ExternalModelSpec external =
      identify::parse_external_spec(spec.model_overrides, "study: model.external");
  std::vector<diagnose::EffectCandidate> out;
  for (const auto& e : external.candidates) {
    std::string reason;
    for (const auto& v : spec.variables)
      if (v.name == e.parameter) reason = "'" + e.parameter + "' is a study variable";
    const auto fixed = spec.fixed_parameters.find(e.parameter);
    if (fixed != spec.fixed_parameters.end() && fixed->second != e.off_value)
      reason = "the study fixes " + e.parameter + " = " + std::to_string(fixed->second) +
               " (off: " + std::to_string(e.off_value) + ")";
    if (!reason.empty()) {
      std::fprintf(stderr, "demfit: note: effect '%s' is not a candidate: %s\n", e.name.c_str(), reason.c_str());
      continue;
    }
    const std::string unit = external.units.at(e.parameter);
    out.push_back({e.name, e.description, {{e.parameter, e.lower, e.upper, e.off_value, unit}}, e.curves});
  }
  return out;
}

// Adds one experiment's candidates to the union over experiments: an effect that applies to
// several experiments is one candidate (its parameter is shared, as the study's variables are)
// acting on all their curves, with the narrowest upper bound any experiment gives it.
void merge_candidates(std::vector<diagnose::EffectCandidate>& into, std::vector<diagnose::EffectCandidate> more) {
  for (auto& c : more) {
    auto same = std::find_if(into.begin(), into.end(), [&](const auto& o) { return o.name == c.name; });
    if (same == into.end()) {
      into.push_back(std::move(c));
      continue;
    }
    const bool all_curves = same->curves.empty() || c.curves.empty();
    same->curves.insert(same->curves.end(), c.curves.begin(), c.curves.end());
    if (all_curves) same->curves.clear();
    for (std::size_t k = 0; k < same->parameters.size() && k < c.parameters.size(); ++k)
      same->parameters[k].upper = std::min(same->parameters[k].upper, c.parameters[k].upper);
  }
}

// One model and its candidate effects. "analytic" gets the analytic family with effect terms
// (same base curve as identify's analytic model); DEM cases get the cases catalogue's effects.
// `experiment` non-empty: curves are qualified "<experiment>/<curve>".
std::unique_ptr<identify::Model> one_model(const std::string& reference, const nlohmann::json& overrides,
                                           const identify::ParameterSet& fixed, const identify::StudySpec& spec,
                                           const std::string& experiment,
                                           std::vector<diagnose::EffectCandidate>& candidates) {
  if (reference == "analytic") {
    int points = 41;
    for (const auto& [key, value] : overrides.items()) {
      if (key != "points" || !value.is_number_integer() || value.get<int>() < 3)
        throw std::runtime_error("study: model.overrides: '" + key +
                                 "' is not understood by diagnose for \"analytic\"; only \"points\" (integer >= 3)");
      points = value.get<int>();
    }
    candidates = diagnose::analytic_effect_candidates();
    if (!experiment.empty())
      for (auto& c : candidates)
        for (auto& curve : c.curves) curve = experiment + "/" + curve;
    return std::make_unique<diagnose::AnalyticEffectsModel>(points);
  }
  auto model = make_model(reference, overrides, spec.base_dir);
  identify::ParameterSet values = model->default_parameters();
  for (const auto& [name, value] : fixed) values[name] = value;
  candidates =
      dem_candidates(resolve_case(reference, overrides, spec.base_dir), values, spec.variables, experiment);
  return model;
}

// The study's model and its candidate effects. An experiments study (e.g. the GranuDrum at 15
// and 45 rpm) gets identify's ExperimentSetModel over one model per experiment and the union
// of their candidates.
}  // namespace

std::unique_ptr<identify::Model> diagnosis_model_and_candidates(const identify::StudySpec& spec,
                                                                std::vector<diagnose::EffectCandidate>& candidates,
                                                                const std::filesystem::path& output_dir) {
  if (spec.model_reference == identify::kExternalModelReference && spec.experiments.empty()) {
    if (output_dir.empty())
      throw std::runtime_error("diagnose: an external model needs an output folder for its runs (external_runs); give one (out=...)");
    auto model = identify::make_external_model(spec, output_dir, identify::OutputKind::diagnose);
    candidates = external_candidates(spec);
    return model;
  }
  if (spec.experiments.empty())
    return one_model(spec.model_reference, spec.model_overrides, spec.fixed_parameters, spec, "", candidates);
  std::vector<std::unique_ptr<identify::Model>> models;
  for (const auto& e : spec.experiments) {
    std::vector<diagnose::EffectCandidate> own;
    models.push_back(one_model(e.model_reference, e.model_overrides, e.fixed_parameters, spec, e.name, own));
    merge_candidates(candidates, std::move(own));
  }
  // identify's evaluators split each point of the set into one job per experiment and join them.
  return std::make_unique<identify::ExperimentSetModel>(spec, std::move(models));
}

// Expensive, chaotic DEM models get diagnose's options for them; the analytic model does not.
bool uses_dem(const identify::StudySpec& spec) {
  if (spec.experiments.empty()) return spec.model_reference != "analytic";
  for (const auto& e : spec.experiments)
    if (e.model_reference != "analytic") return true;
  return false;
}

// diagnose fits least squares at the target points, so an image target's profile_area metric is
// read as mse at the photo's abscissae (the same profile z(x); docs/study_format.md allows both).
identify::StudySpec with_pointwise_metrics(identify::StudySpec spec) {
  for (auto& t : spec.targets) {
    if (t.metric != identify::CurveMetric::profile_area) continue;
    t.metric = identify::CurveMetric::mse;
    std::fprintf(stderr, "demfit: note: target '%s': profile_area is fitted as mse at the target's points\n",
                 t.name.c_str());
  }
  return spec;
}

}  // namespace demfit::cases
