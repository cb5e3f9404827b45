// Case reference -> identify::Model (see model_factory.hpp). The DEM model runs a case with the
// study's parameters applied to the measured stage; the fill comes from the case's own values
// and is cached, so every evaluation of a study starts from the same settled bed.
#include "demfit/cases/model_factory.hpp"

#include "demfit/cases/case_registry.hpp"

#include <stdexcept>

#include "builtin_cases.hpp"
#include "dem_setup.hpp"
#include "demfit/cases/case_runner.hpp"
#include "demfit/cases/case_spec.hpp"
#include "demfit/cases/json_fields.hpp"
#include "demfit/cases/parameter_table.hpp"
#include "demfit/identify/analytic_model.hpp"
#include "demfit/identify/experiments.hpp"

namespace demfit::cases {
namespace {

class DemCaseModel final : public identify::Model {
 public:
  explicit DemCaseModel(CaseSpec spec) : spec_(std::move(spec)) {}
  std::vector<identify::ParameterDescriptor> parameters() const override { return parameter_descriptors(); }
  identify::ParameterSet default_parameters() const override { return detail::parameters_of(spec_); }
  std::vector<identify::CurveDescriptor> curves() const override { return produced_curves(spec_); }
  // EvaluationContext::seed is not used: the fill seed is a case setting, so all evaluations of a
  // study share one settled bed (deterministic, cached).
  identify::CurveSet evaluate(const identify::ParameterSet& parameters,
                              const identify::EvaluationContext& context) const override {
    CaseRunOptions options;
    options.threads = std::max(1, context.threads);
    return run_case(spec_, parameters, options).curves;
  }

 private:
  CaseSpec spec_;
};

// The shipped case file of each kind, compiled in (a reference by kind name resolves to it).
nlohmann::json builtin_document(CaseKind kind) {
  switch (kind) {
    case CaseKind::pellet_compression:
      return nlohmann::json::parse(detail::kBuiltinPelletCompression);
    case CaseKind::rotary_drum:
      return nlohmann::json::parse(detail::kBuiltinRotaryDrum);
    case CaseKind::mesh_container:
      throw std::runtime_error(
          "\"mesh_container\" has no built-in case: give the path of a mesh_container case file (its STL files "
          "are found relative to it), e.g. examples/mesh_container/heap.json");
  }
  throw std::logic_error("a CaseKind without a built-in case file");
}

}  // namespace

std::unique_ptr<identify::Model> make_model(const std::string& reference, const nlohmann::json& overrides,
                                            const std::filesystem::path& base_dir) {
  if (!overrides.is_null() && !overrides.is_object()) {
    throw std::runtime_error("model overrides must be a JSON object of case fields");
  }
  if (reference == "analytic") {
    const nlohmann::json o = overrides.is_null() ? nlohmann::json::object() : overrides;
    require_known_keys(o, "model.overrides", {"points"});
    return std::make_unique<identify::AnalyticCurveModel>(
        static_cast<int>(read_integer(o, "model.overrides", "points", 41, 2)));
  }
  return std::make_unique<DemCaseModel>(resolve_case(reference, overrides, base_dir));
}

std::unique_ptr<identify::Model> make_study_model(const identify::StudySpec& spec) {
  if (spec.experiments.empty()) return make_model(spec.model_reference, spec.model_overrides, spec.base_dir);
  std::vector<std::unique_ptr<identify::Model>> models;
  for (std::size_t e = 0; e < spec.experiments.size(); ++e) {
    const auto& experiment = spec.experiments[e];
    try {
      models.push_back(make_model(experiment.model_reference, experiment.model_overrides, spec.base_dir));
    } catch (const std::exception& error) {
      throw std::runtime_error("study: experiments[" + std::to_string(e) + "] ('" + experiment.name +
                               "').model: " + error.what());
    }
  }
  return std::make_unique<identify::ExperimentSetModel>(spec, std::move(models));
}

CaseSpec resolve_case(const std::string& reference, const nlohmann::json& overrides,
                      const std::filesystem::path& base_dir) {
  // A study with "experiments" has no single model: say so instead of reading base_dir as a file.
  if (reference.empty())
    throw std::runtime_error(
        "no case reference: a study with \"experiments\" has one model per experiment; this "
        "command needs a single-model study (\"model\" + \"targets\")");
  nlohmann::json document;
  std::filesystem::path case_dir = base_dir;  // relative files in the case (size CSV) start here
  if (const CaseKindRow* kind = find_case_kind(reference)) {
    document = builtin_document(kind->kind);
  } else {
    std::filesystem::path path(reference);
    if (path.is_relative()) path = base_dir / path;
    document = read_case_json(path.string());
    case_dir = path.parent_path();
  }
  // RFC 7386 merge patch: study overrides are partial case documents ({"pellet": {"unload": true}}).
  if (overrides.is_object()) document.merge_patch(overrides);
  return parse_case(document, case_dir);
}

}  // namespace demfit::cases
