// demfit diagnose: is the misfit of an identified model noise, or a missing physical effect?
// (workflow in diagnose/include/demfit/diagnose/workflow.hpp, docs/diagnose.md)
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>

#include "cli_safety.hpp"
#include "commands.hpp"
#include "demfit/identify/safe_output.hpp"
#include "demfit/identify/study_preflight.hpp"
#include "demfit/cases/diagnosis_model.hpp"
#include "demfit/cases/study_model.hpp"
#include "demfit/diagnose/effect.hpp"
#include "demfit/diagnose/report.hpp"
#include "demfit/diagnose/workflow.hpp"
#include "demfit/identify/study_spec.hpp"

namespace demfit::apps {
namespace {

struct DiagnoseCliOptions {
  std::string study_file;
  std::string effects;  // comma-separated candidate names; empty = all for the model
  double noise = 0.0;   // y units; 0 = estimate from the data
  std::string out;
  int jobs = 1;
  double alpha = 0.01;
  double bic_threshold = 10.0;
  int refit_best = 2;
  int scatter_replicas = -1;  // -1: the model's default (4 for DEM studies, 0 for the analytic model)
  double data_scatter = 0.0;  // the data's own run-to-run scatter variance / one model run's
  int refit_search = 0;       // model runs of the surrogate search per re-fitted candidate when none passed
  bool no_plots = false;
};

// Documented upper limits: each replica or re-fit costs whole model runs.
constexpr int kMaxScatterReplicas = 64;
constexpr int kMaxRefitBest = 64;
constexpr int kMaxDataScatter = 16;
constexpr int kMaxRefitSearch = 400;

void run_diagnose(const DiagnoseCliOptions& o) {
  if (o.jobs < 1) throw std::runtime_error("--jobs: must be >= 1");
  require_finite(o.noise, "--noise");
  require_finite(o.alpha, "--alpha");
  require_finite(o.bic_threshold, "--bic-threshold");
  if (o.noise < 0.0)
    throw std::runtime_error("--noise: must be > 0 (y units of the targets), or omitted to estimate it");
  if (!(o.alpha > 0.0 && o.alpha < 1.0)) throw std::runtime_error("--alpha: must be in (0, 1), e.g. 0.01");
  if (o.refit_best < 1) throw std::runtime_error("--refit-best: must be >= 1");
  if (o.scatter_replicas < -1)
    throw std::runtime_error("--scatter-replicas: must be >= 0 (0 = data noise alone; e.g. 4 replica runs)");
  require_at_most(o.scatter_replicas, kMaxScatterReplicas, "--scatter-replicas",
                  "a few replica runs measure the scatter (default 4 for DEM studies)");
  require_finite(o.data_scatter, "--data-scatter");
  if (o.data_scatter < 0.0 || o.data_scatter > kMaxDataScatter)
    throw std::runtime_error("--data-scatter: must be in [0, " + std::to_string(kMaxDataScatter) +
                             "] (0 = the data's own scatter is negligible, 1 = the data are one run of a model like "
                             "this one, 1/m = a mean of m such runs)");
  require_at_most(o.refit_best, kMaxRefitBest, "--refit-best", "each re-fit is a full identification (default 2)");
  if (o.refit_search < 0) throw std::runtime_error("--refit-search: must be >= 0 (0 = none; e.g. 30 model runs)");
  require_at_most(o.refit_search, kMaxRefitSearch, "--refit-search",
                  "each is a model run; 30 were measured for two variables");
  const identify::StudySpec spec = cases::with_pointwise_metrics(identify::load_study_file(o.study_file));
  const std::filesystem::path out =
      o.out.empty() ? std::filesystem::path(std::filesystem::path(o.study_file).stem().string() + "_diagnosis")
                    : std::filesystem::path(o.out);
  // Output folder rules before any work; created, marked, when the diagnosis is written.
  const identify::OutputRequest request{identify::OutputKind::diagnose, cases::study_input_files(spec, o.study_file)};
  identify::check_output_folder(out, request);
  std::vector<diagnose::EffectCandidate> candidates;
  const auto model = cases::diagnosis_model_and_candidates(spec, candidates, out);
  const bool dem = cases::uses_dem(spec);
  if (!o.effects.empty()) candidates = diagnose::select_candidates(candidates, o.effects);
  diagnose::DiagnoseOptions options = dem ? diagnose::expensive_model_options() : diagnose::DiagnoseOptions{};
  options.noise_sigma = o.noise;
  options.alpha = o.alpha;
  options.bic_threshold = o.bic_threshold;
  options.refit_best = o.refit_best;
  if (o.scatter_replicas >= 0) options.scatter_replicas = o.scatter_replicas;
  options.data_scatter_ratio = o.data_scatter;
  options.refit_search_evaluations = o.refit_search;
  options.progress = true;  // DEM diagnoses take minutes: say what is running
  options.fit.jobs = o.jobs;
  options.fit.seed = spec.seed;
  // Curve names, units and x-overlap checked at the initial point, as for identify; a
  // study's experiments run side by side over --jobs.
  identify::ThreadPoolEvaluator preflight_pool(*model, o.jobs, 1, static_cast<unsigned long>(spec.seed));
  const identify::StudySpec checked = identify::preflight_study(spec, *model, preflight_pool);
  const diagnose::Diagnosis d = diagnose::run_diagnosis(checked, *model, candidates, options);
  identify::prepare_output_folder(out, request);
  const std::string warnings = diagnose::write_diagnosis(d, out, !o.no_plots);
  if (!warnings.empty()) std::fprintf(stderr, "demfit: %s", warnings.c_str());
  std::printf("verdict: %s%s\n%s\nresults: %s\n", diagnose::verdict_text(d.verdict),
              d.chosen >= 0 ? (" — " + d.refits[d.chosen].effect).c_str() : "", d.summary.c_str(),
              identify::printable((out / "report.md").string()).c_str());
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
      "or ambiguous residual. See docs/diagnose.md. Writes report.md, report.html (the same, one self-contained "
      "page), diagnosis.json, diagnosis_<target>.png. "
      "Candidates: "
      "for pellet_compression / rotary_drum studies the effects of the cases catalogue that apply to the case "
      "(plasticity, "
      "cohesion, hertz_stiffness, wall_friction, rolling_resistance, polydispersity; one already on in the model is "
      "left "
      "out); for the \"analytic\" model toe_shift, stiffening, yield_drop; for an external program the study's "
      "model.external.candidates (template parameters with off values and ranges, docs/external-model.md; runs in "
      "<out>/external_runs). DEM fits use central differences of 2 % of "
      "each "
      "range and about 100 evaluations. Targets must use metric \"mse\" (a loading-unloading curve is matched branch "
      "by branch; "
      "profile_area targets are fitted as mse at their points). A study with \"experiments\" is diagnosed as one model "
      "over all "
      "experiments, with the union of their candidates.");
  cmd->add_option("study", o->study_file, "Study file (JSON, docs/study_format.md)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--effects", o->effects,
                  "Comma-separated candidate effects to consider (default: all that apply to the model or case)");
  cmd->add_option("--noise", o->noise,
                  "Noise standard deviation of the target y values, in the targets' y units (default: estimated "
                  "from successive differences of each target)");
  cmd->add_option("--out", o->out, "Output folder (default: <study file stem>_diagnosis)")->check(non_empty_path());
  cmd->add_option("--jobs", o->jobs, "Model evaluations at once (default 1); results do not depend on it");
  cmd->add_option("--alpha", o->alpha,
                  "Family-wise level of the tests that call the base residual structural (default 0.01)");
  cmd->add_option("--bic-threshold", o->bic_threshold, "BIC improvement needed to name an effect (default 10)");
  cmd->add_option("--refit-best", o->refit_best,
                  "Candidates re-identified after screening: at least this many (default 2), plus every one scoring at "
                  "least 1/4 of the best (DEM models) or all of them (analytic model)");
  cmd->add_option("--scatter-replicas", o->scatter_replicas,
                  "Runs of the base optimum moved by round-off-sized steps that measure the model's own trajectory "
                  "scatter (y units, per target); where it exceeds 1/4 of the data noise it joins the noise model as "
                  "correlated noise and residuals are whitened (default 4 for DEM studies, 0 for the analytic model; "
                  "0 = data noise alone; at most 64)");
  cmd->add_option("--data-scatter", o->data_scatter,
                  "The data's own run-to-run scatter as a multiple of one model run's scatter variance (a ratio, no "
                  "units), counted in the noise model beside the model run's: 0 (default) = negligible (data averaged "
                  "over many realisations, or a material with far more particles than the model); 1 = the data are one "
                  "run of a model like this one (a synthetic twin from `demfit simulate`); 1/m for a mean of m such "
                  "runs; at most " + std::to_string(kMaxDataScatter));
  cmd->add_option("--refit-search", o->refit_search,
                  "Model runs of a global surrogate search (maximin design + kriging expected improvement over base + "
                  "effect variables) made for each re-fitted candidate when none passed with its local starts; its "
                  "point of lowest predicted chi-square is assessed, then fitted locally; when the model scatters, the "
                  "base variables get the same search first and the base is judged at the better of its two optima "
                  "(default 0 = none; 30 measured for two variables; at most " + std::to_string(kMaxRefitSearch) + ")");
  cmd->add_flag("--no-plots", o->no_plots, "Do not call gnuplot");
  cmd->callback([o] { run_diagnose(*o); });
}
}  // namespace demfit::apps
