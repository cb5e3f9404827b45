// What a study simulates: its model, the resolved form recorded in its store, its input files.
#include "demfit/cases/study_model.hpp"

#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <system_error>

#include "demfit/cases/case_spec.hpp"
#include "demfit/cases/model_factory.hpp"
#include "demfit/identify/evaluator.hpp"
#include "demfit/identify/external_model.hpp"
#include "demfit/identify/safe_output.hpp"
#include "demfit/identify/store_lock.hpp"
#include "demfit/identify/study_preflight.hpp"
#include "demfit/identify/relative_axis.hpp"

namespace demfit::cases {

std::unique_ptr<identify::Model> make_identify_model(const identify::StudySpec& spec,
                                                     const std::filesystem::path& output_dir) {
  for (const auto& e : spec.experiments)
    if (e.model_reference == identify::kExternalModelReference)
      throw std::runtime_error("study: experiments: '" + e.name +
                               "' has an external model; an external program is for a single-model study "
                               "(\"model\" + \"targets\")");
  std::unique_ptr<identify::Model> model = spec.model_reference == identify::kExternalModelReference
                                               ? identify::make_external_model(spec, output_dir)
                                               : make_study_model(spec);
  std::set<std::string> relative;
  for (const auto& t : spec.targets)
    if (t.curve.find('@') != std::string::npos) relative.insert(t.curve);
  if (relative.empty()) return model;
  return std::make_unique<identify::RelativeAxisModel>(std::move(model), std::move(relative));
}

std::unique_ptr<identify::Model> make_cheap_level_model(const identify::StudySpec& spec,
                                                        const std::filesystem::path& output_dir) {
  if (!spec.cheap_level) return nullptr;
  try {
    return make_identify_model(identify::cheap_level_study(spec), output_dir / "cheap_level");
  } catch (const std::exception& e) {  // the case's own message, said to come from the cheap level
    throw std::runtime_error(std::string("study: cheap_level.overrides: ") + e.what());
  }
}

namespace {
// The content of a case, not its path, so that a resumed study refuses any change to what is simulated.
nlohmann::json resolved_one_model(const std::string& reference, const nlohmann::json& overrides,
                                  const std::filesystem::path& base_dir) {
  if (reference == "analytic") return {{"analytic", overrides}};
  if (reference == identify::kExternalModelReference) return identify::resolved_external_model(overrides, base_dir);
  return to_json(resolve_case(reference, overrides, base_dir));
}
}  // namespace

nlohmann::json resolved_study_model(const identify::StudySpec& spec) {
  if (spec.experiments.empty()) return resolved_one_model(spec.model_reference, spec.model_overrides, spec.base_dir);
  nlohmann::json experiments = nlohmann::json::object();
  for (const auto& e : spec.experiments)
    experiments[e.name] = resolved_one_model(e.model_reference, e.model_overrides, spec.base_dir);
  return experiments;
}

std::vector<std::filesystem::path> study_input_files(const identify::StudySpec& spec,
                                                     const std::filesystem::path& study_file) {
  std::vector<std::filesystem::path> inputs{study_file};
  for (const auto& t : spec.targets)
    if (!t.csv.empty()) inputs.push_back(t.csv.is_absolute() ? t.csv : spec.base_dir / t.csv);
  std::error_code error;
  const std::filesystem::path case_file = spec.base_dir / spec.model_reference;
  if (std::filesystem::is_regular_file(case_file, error)) inputs.push_back(case_file);
  return inputs;
}

identify::StudyResult run_study_file(const identify::StudySpec& parsed, const std::filesystem::path& study_file,
                                     identify::RunOptions options, std::string_view resume_hint,
                                     std::string_view out_option) {
  identify::OutputRequest request{identify::OutputKind::identify, study_input_files(parsed, study_file)};
  request.option = std::string(out_option);
  std::optional<identify::StoreLock> lock;
  identify::claim_study_folder(options, request, lock, resume_hint);
  const auto model = make_identify_model(parsed, options.output_dir);
  const auto cheap_model = make_cheap_level_model(parsed, options.output_dir);
  options.cheap_model = cheap_model.get();
  options.resolved_model = resolved_study_model(parsed);
  // One pool for the initial-point check and the loop: the check's experiments run side by side
  // over the jobs, and the run it hands over is the loop's own (on --resume, the stored run 0/0
  // when the store holds it: no evaluation at all).
  identify::ThreadPoolEvaluator pool(*model, options.jobs, options.threads_per_job,
                                     static_cast<unsigned long>(parsed.seed));
  const identify::StudySpec spec = identify::preflight_study(parsed, *model, pool, options);
  request.lock_held = lock.has_value();
  identify::prepare_output_folder(options.output_dir, request);
  if (!lock) lock.emplace(options.output_dir);
  options.evaluator = &pool;
  return identify::run_study(spec, *model, options);
}

}  // namespace demfit::cases
