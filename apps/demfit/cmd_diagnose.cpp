// demfit diagnose: is the misfit of an identified model noise, or a missing physical effect?
// (issue #6; workflow in diagnose/include/demfit/diagnose/workflow.hpp, docs/diagnose.md)
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>

#include "cli_safety.hpp"
#include "commands.hpp"
#include "demfit/identify/safe_output.hpp"
#include "demfit/identify/study_preflight.hpp"
#include "demfit/cases/case_spec.hpp"
#include "demfit/cases/effect_catalogue.hpp"
#include "demfit/cases/model_factory.hpp"
#include "demfit/diagnose/analytic_effects_model.hpp"
#include "demfit/diagnose/effect.hpp"
#include "demfit/diagnose/report.hpp"
#include "demfit/diagnose/workflow.hpp"
#include "demfit/identify/study_spec.hpp"

namespace demfit::apps {
namespace {

struct DiagnoseCliOptions {
  std::string study_file;
  std::string effects;          // comma-separated candidate names; empty = all for the model
  double noise = 0.0;           // y units; 0 = estimate from the data
  std::string out;
  int jobs = 1;
  double alpha = 0.01;
  double bic_threshold = 10.0;
  int refit_best = 2;
  bool no_plots = false;
};

// The cases catalogue (cases/effect_catalogue.hpp) as diagnose candidates: the effects that apply
// to the study's case. An effect is left out, with a note, when one of its parameters is a study
// variable or already differs from its off value in the model (the effect is then part of the
// base model, not a candidate).
std::vector<diagnose::EffectCandidate> dem_candidates(const identify::StudySpec& spec, const identify::Model& model) {
  identify::ParameterSet values = model.default_parameters();
  for (const auto& [name, value] : spec.fixed_parameters) values[name] = value;
  std::vector<diagnose::EffectCandidate> out;
  for (const auto& effect : cases::effects_for_case(cases::resolve_case(spec.model_reference, spec.model_overrides, spec.base_dir))) {
    diagnose::EffectCandidate c{effect.name, effect.description, {}, effect.curves};
    std::string reason;
    for (const auto& p : effect.parameters) {
      c.parameters.push_back({p.name, p.lower, p.upper, p.off_value});
      for (const auto& v : spec.variables)
        if (v.name == p.name) reason = "'" + p.name + "' is a study variable";
      const auto found = values.find(p.name);
      if (reason.empty() && found != values.end() && found->second != p.off_value)
        reason = "the model already has " + p.name + " = " + std::to_string(found->second) + " (off: " +
                 std::to_string(p.off_value) + ")";
    }
    if (reason.empty()) {
      out.push_back(std::move(c));
    } else {
      std::fprintf(stderr, "demfit: note: effect '%s' is not a candidate: %s\n", effect.name.c_str(), reason.c_str());
    }
  }
  return out;
}

// The model and its candidate effects. "analytic" gets the analytic family with effect terms
// (same base curve as identify's analytic model); DEM cases get the cases catalogue's effects
// and the options for expensive, chaotic models.
std::unique_ptr<identify::Model> model_and_candidates(const identify::StudySpec& spec,
                                                      std::vector<diagnose::EffectCandidate>& candidates) {
  if (spec.model_reference == "analytic") {
    int points = 41;
    for (const auto& [key, value] : spec.model_overrides.items()) {
      if (key != "points" || !value.is_number_integer() || value.get<int>() < 3)
        throw std::runtime_error("study: model.overrides: '" + key +
                                 "' is not understood by diagnose for \"analytic\"; only \"points\" (integer >= 3)");
      points = value.get<int>();
    }
    candidates = diagnose::analytic_effect_candidates();
    return std::make_unique<diagnose::AnalyticEffectsModel>(points);
  }
  auto model = cases::make_model(spec.model_reference, spec.model_overrides, spec.base_dir);
  candidates = dem_candidates(spec, *model);
  return model;
}

void run_diagnose(const DiagnoseCliOptions& o) {
  if (o.jobs < 1) throw std::runtime_error("--jobs: must be >= 1");
  require_finite(o.noise, "--noise");
  require_finite(o.alpha, "--alpha");
  require_finite(o.bic_threshold, "--bic-threshold");
  if (o.noise < 0.0) throw std::runtime_error("--noise: must be > 0 (y units of the targets), or omitted to estimate it");
  if (!(o.alpha > 0.0 && o.alpha < 1.0)) throw std::runtime_error("--alpha: must be in (0, 1), e.g. 0.01");
  if (o.refit_best < 1) throw std::runtime_error("--refit-best: must be >= 1");
  const identify::StudySpec spec = identify::load_study_file(o.study_file);
  const std::filesystem::path out =
      o.out.empty() ? std::filesystem::path(std::filesystem::path(o.study_file).stem().string() + "_diagnosis")
                    : std::filesystem::path(o.out);
  // Output folder rules before any work (issue #13); created, marked, when the diagnosis is written.
  identify::check_output_folder(out, study_inputs(spec, o.study_file), "--out");
  std::vector<diagnose::EffectCandidate> candidates;
  const auto model = model_and_candidates(spec, candidates);
  const bool dem = spec.model_reference != "analytic";
  if (!o.effects.empty()) candidates = diagnose::select_candidates(candidates, o.effects);
  diagnose::DiagnoseOptions options = dem ? diagnose::expensive_model_options() : diagnose::DiagnoseOptions{};
  options.noise_sigma = o.noise;
  options.alpha = o.alpha;
  options.bic_threshold = o.bic_threshold;
  options.refit_best = o.refit_best;
  options.progress = true;  // DEM diagnoses take minutes: say what is running
  options.fit.jobs = o.jobs;
  options.fit.seed = spec.seed;
  // Curve names, units and x-overlap checked at the initial point, as for identify (issue #13).
  const identify::StudySpec checked =
      identify::preflight_study(spec, *model, {1, static_cast<unsigned long>(spec.seed)});
  const diagnose::Diagnosis d = diagnose::run_diagnosis(checked, *model, candidates, options);
  identify::prepare_output_folder(out, study_inputs(spec, o.study_file), "--out");
  const std::string warnings = diagnose::write_diagnosis(d, out, !o.no_plots);
  if (!warnings.empty()) std::fprintf(stderr, "demfit: %s", warnings.c_str());
  std::printf("verdict: %s%s\n%s\nresults: %s\n", diagnose::verdict_text(d.verdict),
              d.chosen >= 0 ? (" — " + d.refits[d.chosen].effect).c_str() : "", d.summary.c_str(),
              (out / "report.md").string().c_str());
}

}  // namespace

void register_diagnose(CLI::App& app) {
  auto o = std::make_shared<DiagnoseCliOptions>();
  auto* cmd = app.add_subcommand(
      "diagnose",
      "Fit the study's base model (local least squares from the study's initial values), test whether the "
      "residual is noise (runs, lag-1 autocorrelation, variance vs the noise level, smooth-structure projection) "
      "and, if not, screen candidate effects by a score test, re-fit the best few and name one only if BIC improves "
      "by more than the threshold AND the residual becomes noise (tests at 5 %); otherwise report an unexplained "
      "or ambiguous residual. See docs/diagnose.md. Writes report.md, diagnosis.json, diagnosis_<target>.png. Candidates: "
      "for pellet_compression / rotary_drum studies the effects of the cases catalogue that apply to the case (plasticity, "
      "cohesion, hertz_stiffness, wall_friction, rolling_resistance, polydispersity; one already on in the model is left "
      "out); for the \"analytic\" model toe_shift, stiffening, yield_drop. DEM fits use central differences of 2 % of each "
      "range and about 100 evaluations. Targets must use metric \"mse\" (a loading-unloading curve is matched branch by branch).");
  cmd->add_option("study", o->study_file, "Study file (JSON, docs/study_format.md)")->required()->check(CLI::ExistingFile);
  cmd->add_option("--effects", o->effects, "Comma-separated candidate effects to consider (default: all that apply to the model or case)");
  cmd->add_option("--noise", o->noise,
                  "Noise standard deviation of the target y values, in the targets' y units (default: estimated "
                  "from successive differences of each target)");
  cmd->add_option("--out", o->out, "Output folder (default: <study file stem>_diagnosis)");
  cmd->add_option("--jobs", o->jobs, "Model evaluations at once (default 1); results do not depend on it");
  cmd->add_option("--alpha", o->alpha, "Family-wise level of the tests that call the base residual structural (default 0.01)");
  cmd->add_option("--bic-threshold", o->bic_threshold, "BIC improvement needed to name an effect (default 10)");
  cmd->add_option("--refit-best", o->refit_best, "Candidates re-identified after screening: at least this many (default 2), plus every one scoring at "
                  "least 1/4 of the best (DEM models) or all of them (analytic model)");
  cmd->add_flag("--no-plots", o->no_plots, "Do not call gnuplot");
  cmd->callback([o] { run_diagnose(*o); });
}
}  // namespace demfit::apps
