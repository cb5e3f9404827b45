// The resolved study as JSON (study_resolved.json, the store's record) and its hash, the study's
// identity for resume (study_spec.hpp).
#include <string>
#include <type_traits>
#include <variant>

#include "demfit/identify/external_model.hpp"
#include "demfit/identify/study_spec.hpp"

namespace demfit::identify {
namespace {

std::string metric_name(CurveMetric metric) {
  switch (metric) {
    case CurveMetric::mse:
      return "mse";
    case CurveMetric::curve_mapping:
      return "curve_mapping";
    case CurveMetric::profile_area:
      return "profile_area";
  }
  return "mse";
}

nlohmann::json model_json(const std::string& reference, const nlohmann::json& overrides, const ParameterSet& fixed) {
  nlohmann::json json = reference == kExternalModelReference
                            ? nlohmann::json{{"external", overrides}, {"fixed_parameters", nlohmann::json::object()}}
                            : nlohmann::json{{"case", reference},
                                             {"overrides", overrides},
                                             {"fixed_parameters", nlohmann::json::object()}};
  for (const auto& [name, value] : fixed) json["fixed_parameters"][name] = value;
  return json;
}

// A resolved target: data inline, "source" = where it came from (informational, not hashed).
nlohmann::json target_json(const TargetSpec& t, const std::string& name, const std::string& curve) {
  nlohmann::json target = {{"name", name},
                           {"curve", curve},
                           {"x_column", t.data.x_label},
                           {"y_column", t.data.y_label},
                           {"x", t.data.x},
                           {"y", t.data.y},
                           {"metric", metric_name(t.metric)},
                           {"weight", t.weight},
                           {"scale", t.scale},
                           {"mapping_points", t.mapping_points}};
  if (!t.csv.empty())
    target["source"] = t.csv.generic_string();
  else if (t.image)
    target["source"] = t.image->file.generic_string();
  return target;
}

}  // namespace

nlohmann::json to_json(const StudySpec& spec) {
  nlohmann::json json;
  json["demfit_study_version"] = spec.version;
  json["name"] = spec.name;
  json["variables"] = nlohmann::json::array();
  for (const auto& v : spec.variables)
    json["variables"].push_back({{"name", v.name},
                                 {"lower", v.lower},
                                 {"upper", v.upper},
                                 {"initial", v.initial},
                                 {"log_scale", v.log_scale},
                                 {"initial_range", v.initial_range}});
  if (spec.experiments.empty()) {
    json["model"] = model_json(spec.model_reference, spec.model_overrides, spec.fixed_parameters);
    json["targets"] = nlohmann::json::array();
    for (const auto& t : spec.targets) json["targets"].push_back(target_json(t, t.name, t.curve));
  } else {
    json["experiments"] = nlohmann::json::array();
    for (const auto& e : spec.experiments) {
      nlohmann::json targets = nlohmann::json::array();
      for (const auto& t : spec.targets)
        if (t.experiment == e.name)
          targets.push_back(target_json(t, t.name.substr(e.name.size() + 1), t.curve.substr(e.name.size() + 1)));
      json["experiments"].push_back({{"name", e.name},
                                     {"model", model_json(e.model_reference, e.model_overrides, e.fixed_parameters)},
                                     {"targets", targets}});
    }
  }
  json["sampling"] = {{"points_per_iteration", spec.points_per_iteration}, {"strategy", strategy_name(spec.strategy)}};
  json["domain_reduction"] = {{"gamma_pan", spec.gamma_pan}, {"gamma_osc", spec.gamma_osc}, {"eta", spec.eta}};
  json["surrogate"] = {
      {"basis", spec.basis},
      {"responses", spec.responses == ResponseMode::curve_points ? "curve_points" : "principal_components"},
      {"smoothing", spec.smoothing}};
  json["stopping"] = {{"max_iterations", spec.max_iterations},
                      {"design_tolerance", spec.design_tolerance},
                      {"objective_tolerance", spec.objective_tolerance}};
  if (spec.max_runs > 0) json["stopping"]["max_runs"] = spec.max_runs;  // written only when set
  if (spec.max_wall_seconds > 0.0) json["stopping"]["max_wall_seconds"] = spec.max_wall_seconds;
  if (spec.verification_tolerance > 0.0) json["stopping"]["verification_tolerance"] = spec.verification_tolerance;
  if (spec.interval_check.max_steps > 0)  // written only when on: older resolved studies stay unchanged
    json["interval_check"] = {{"max_steps", spec.interval_check.max_steps},
                              {"replicates", spec.interval_check.replicates},
                              {"first_step", spec.interval_check.first_step},
                              {"all_variables", spec.interval_check.all_variables}};
  // Written only when on: older resolved studies, and so their hashes, stay unchanged.
  std::visit(
      [&](const auto& method) {
        using Method = std::decay_t<decltype(method)>;
        if constexpr (std::is_same_v<Method, ReplicateSelection>) {
          json["final_selection"] = {{"candidates", method.candidates}, {"replicates", method.replicates}};
        } else if constexpr (std::is_same_v<Method, PredictedOptimumSelection>) {
          json["final_selection"] = {{"method", Method::name}};
        } else {  // a new method fails to compile here until it is written
          static_assert(std::is_same_v<Method, LowestRunSelection>);
        }
      },
      spec.final_selection);
  if (spec.cheap_level)  // written only when declared: one-level studies keep their hashes
    json["cheap_level"] = {{"overrides", spec.cheap_level->overrides}, {"runs", spec.cheap_level->runs}};
  json["seed"] = spec.seed;
  return json;
}

std::uint64_t study_hash(const StudySpec& spec) {
  // FNV-1a 64 over the resolved JSON text: stable across runs and compilers (std::hash is not).
  // The stopping rule is left out so that a finished study can be resumed with a larger
  // iteration limit; informational "source" paths are left out (the data itself is hashed). The
  // interval check runs after the loop, so a finished study can be resumed to add it.
  nlohmann::json json = to_json(spec);
  json.erase("stopping");
  // The stable-answer rule decides what an iteration runs (a verification alone), so a store
  // keeps the tolerance it was run with; only a study with the rule on hashes it, so the stores
  // of studies without it open as before.
  if (spec.verification_tolerance > 0.0) json["verification_tolerance"] = spec.verification_tolerance;
  json.erase("interval_check");
  // An external run's time limit bounds how long it may take, not what it computes.
  if (json.contains("model") && json["model"].contains("external")) json["model"]["external"].erase("time_limit_s");
  if (json.contains("targets"))
    for (auto& target : json["targets"]) target.erase("source");
  if (json.contains("experiments"))
    for (auto& experiment : json["experiments"])
      for (auto& target : experiment["targets"]) target.erase("source");
  const std::string text = json.dump();
  std::uint64_t hash = 14695981039346656037ull;
  for (unsigned char c : text) {
    hash ^= c;
    hash *= 1099511628211ull;
  }
  return hash;
}

}  // namespace demfit::identify
