// demfit.diagnose: the discrepancy workflow (diagnose/workflow.hpp) on a study, as `demfit diagnose
// STUDY` runs it (the same model and candidates, cases/diagnosis_model.hpp): the base fit, the
// residual tests and, when the residual is structural, the candidate effects screened, re-fitted
// and named only when BIC improves by more than the threshold and the residual becomes noise.
#include <filesystem>
#include <optional>
#include <string>

#include "bindings.hpp"
#include "demfit/cases/diagnosis_model.hpp"
#include "demfit/cases/study_model.hpp"
#include "demfit/diagnose/effect.hpp"
#include "demfit/diagnose/report.hpp"
#include "demfit/diagnose/workflow.hpp"
#include "demfit/identify/evaluator.hpp"
#include "demfit/identify/safe_output.hpp"
#include "demfit/identify/study_preflight.hpp"
#include "demfit/identify/study_spec.hpp"

namespace demfit::python {

namespace {

py::dict fit_summary(const diagnose::CandidateFit& fit) {
  py::dict out;
  out["effect"] = fit.effect;
  out["delta_bic"] = fit.delta_bic;
  out["delta_aicc"] = fit.delta_aicc;
  out["passes"] = fit.passes;
  out["parameters"] = to_python(fit.fit.parameters);
  return out;
}

py::dict run(const std::filesystem::path& study_file, const std::optional<std::string>& effects, double noise,
             double alpha, double bic_threshold, int refit_best, int jobs,
             const std::optional<std::filesystem::path>& out, bool plots) {
  if (jobs < 1) input_error("jobs: must be >= 1");
  if (!(noise >= 0.0)) input_error("noise: must be > 0 (y units of the targets), or 0 to estimate it");
  if (!(alpha > 0.0 && alpha < 1.0)) input_error("alpha: must be in (0, 1), e.g. 0.01");
  if (refit_best < 1) input_error("refit_best: must be >= 1");
  const identify::StudySpec spec = cases::with_pointwise_metrics(identify::load_study_file(study_file));
  const identify::OutputRequest request{identify::OutputKind::diagnose, cases::study_input_files(spec, study_file)};
  if (out) identify::check_output_folder(*out, request);
  std::vector<diagnose::EffectCandidate> candidates;
  const auto model = cases::diagnosis_model_and_candidates(spec, candidates, out.value_or(std::filesystem::path{}));
  if (effects) candidates = diagnose::select_candidates(candidates, *effects);
  diagnose::DiagnoseOptions options = cases::uses_dem(spec) ? diagnose::expensive_model_options()
                                                             : diagnose::DiagnoseOptions{};
  options.noise_sigma = noise;
  options.alpha = alpha;
  options.bic_threshold = bic_threshold;
  options.refit_best = refit_best;
  options.fit.jobs = jobs;
  options.fit.seed = spec.seed;
  diagnose::Diagnosis d;
  {
    py::gil_scoped_release release;
    identify::ThreadPoolEvaluator pool(*model, jobs, 1, static_cast<unsigned long>(spec.seed));
    const identify::StudySpec checked = identify::preflight_study(spec, *model, pool);
    d = diagnose::run_diagnosis(checked, *model, candidates, options);
    if (out) {
      identify::prepare_output_folder(*out, request);
      diagnose::write_diagnosis(d, *out, plots);
    }
  }
  py::dict result;
  result["verdict"] = diagnose::verdict_text(d.verdict);
  result["effect"] = d.chosen >= 0 ? py::object(py::str(d.refits[d.chosen].effect)) : py::object(py::none());
  result["summary"] = d.summary;
  result["base_parameters"] = to_python(d.base.parameters);
  result["base_bic"] = d.base_bic;
  py::list refits;
  for (const auto& f : d.refits) refits.append(fit_summary(f));
  result["refits"] = refits;
  result["notes"] = d.notes;
  result["evaluations"] = d.evaluations;
  return result;
}

}  // namespace

void register_diagnose(py::module_& m) {
  m.def("diagnose", &run, py::arg("study"), py::arg("effects") = py::none(), py::arg("noise") = 0.0,
        py::arg("alpha") = 0.01, py::arg("bic_threshold") = 10.0, py::arg("refit_best") = 2, py::arg("jobs") = 1,
        py::arg("out") = py::none(), py::arg("plots") = false,
        "Diagnose a study as `demfit diagnose STUDY` does (analytic or DEM model, experiments too) and return a dict: verdict (the "
        "report's words), effect (the named effect or None), summary, base_parameters, base_bic, refits (effect, "
        "delta_bic, delta_aicc, passes, parameters), notes, evaluations.\n"
        "effects: comma-separated candidates (default all of the model's; `demfit diagnose --help` lists them). noise: the targets' "
        "noise sigma in y units (0 = estimated). out: also write report.md and diagnosis.json there. The GIL is "
        "released during the fits.");
}

}  // namespace demfit::python
