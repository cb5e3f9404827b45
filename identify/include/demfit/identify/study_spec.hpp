#pragma once
// The study file, typed. A study says which model to run (case reference + fixed settings),
// which parameters to vary and within which bounds, which measured curves to match and how,
// and how the LS-OPT-like loop samples, reduces its region and stops (docs/spec.md section 3).
// The JSON format is documented in docs/study_format.md; parsing is strict: unknown keys,
// wrong types and inconsistent values are errors naming the field (one line).
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

#include "demfit/identify/model.hpp"

namespace demfit::identify {

// Current version of the study-file format ("demfit_study_version").
inline constexpr int kStudyFormatVersion = 1;

// One identified variable. Bounds and initial value in the model's parameter units.
struct VariableSpec {
  std::string name;
  double lower = 0.0;
  double upper = 1.0;
  double initial = 0.5;
  bool log_scale = false;      // sample and fit in log(value) (needs lower > 0)
  double initial_range = 1.0;  // width of the iteration-0 region as a fraction of the bounds
};

enum class CurveMetric {
  mse,            // docs/spec.md 3 MSE composite at the target abscissae (needs monotone x)
  curve_mapping,  // area-like distance to the best-aligned equal-arc-length segment
  profile_area,   // area between two profiles z(x) over their common x-range (objective.hpp)
};

// A target read from a drum photo: the free-surface profile extracted by
// demfit::imaging, in the drum frame (origin on the axis, x right, z up), as a curve x_mm, z_mm.
struct ImageTargetSpec {
  std::filesystem::path file;    // as written in the study (relative to the study file)
  double diameter = 0.0;         // [m] inner drum diameter the square picture spans
  double threshold = -1.0;       // grey level in [0, 1]; < 0 = automatic (Otsu)
  bool material_is_dark = true;  // "image_material": "dark" (photos) or "light" (inverted)
  double margin = 0.1;           // fraction of the radius ignored near the drum outline
  int points = 41;               // abscissae of the profile across the usable chord
};

// One measured curve to match. In a study with several experiments, `name` and `curve` are
// qualified by the experiment: name "<experiment>.<target>" (unique in the study, used in file
// names), curve "<experiment>/<curve>" (the key in the CurveSet of a design point, which is the
// union of its experiments' curves; experiments.hpp). to_json writes them unqualified again.
struct TargetSpec {
  std::string name;           // unique; used in file names and reports
  std::string curve;          // simulated curve name in the (design point's) CurveSet
  Curve data;                 // measured points (loaded from CSV or given inline)
  std::filesystem::path csv;  // where data came from (empty when inline)
  CurveMetric metric = CurveMetric::mse;
  double weight = 1.0;                        // weight of this target in the composite objective
  double scale = 0.0;                         // s_p of docs/spec.md 3; 0 = max|G| of the target
  int mapping_points = 0;                     // curve mapping: stations along the curve; 0 = target size
  std::string experiment = {};                // experiment the target belongs to; "" in the single-model form
  std::optional<ImageTargetSpec> image = {};  // where data came from when read from a photo
};

// One experiment of a study with several: a model (case reference + its own
// fixed settings and parameters) whose targets share the study's variables. A variable is
// passed to every experiment whose model accepts it; one that no model accepts is an error.
struct ExperimentSpec {
  std::string name;  // letters, digits, '_' and '-'; unique in the study
  std::string model_reference;
  nlohmann::json model_overrides = nlohmann::json::object();
  ParameterSet fixed_parameters;
};

enum class SamplingStrategy {
  srsm,                  // docs/spec.md 3 domain reduction: optimum + maximin points in the subregion
  adaptive_infill,       // full region; optimum + infill points chosen from the objective model
  expected_improvement,  // full region; optimum + batch expected improvement on the composite objective
};

// "srsm", "adaptive_infill" or "expected_improvement" (the study-file spelling).
const char* strategy_name(SamplingStrategy strategy);

enum class ResponseMode {
  curve_points,          // one RBF output per resampled curve value (shared factorisation)
  principal_components,  // RBF outputs = PCA scores of the stacked curves
};

// Runs at the posterior intervals' ends after the loop (interval_check.hpp): they
// widen an interval the local surrogate drew too narrow. Off when max_steps is 0.
struct IntervalCheckSpec {
  int max_steps = 0;         // outward steps per interval end (each doubles the distance); 0 = off
  int replicates = 2;        // nudged re-runs of the best point measuring the run-to-run spread
  double first_step = 0.02;  // smallest first distance from the best point (fraction of the range)
  // false: only variables whose interval reaches beyond the runs the posterior was fitted to
  bool all_variables = true;
};

// Most round-off replicates a selection or an interval check may ask for (roundoff_replicates.hpp).
inline constexpr int kMaxReplicates = 20;

// How the study picks its answer after the loop ("final_selection" in a study file). On a noisy
// objective the lowest single run is partly the luckiest trajectory, so two alternatives exist:
// re-run the best runs as round-off replicates and take the lowest mean (final_selection.hpp), or
// answer with the verification run at the surrogate's final predicted optimum, whose curves pool
// the noise of the runs around it (Table 1 with expected improvement, 16 seeds:
// docs/measurements/2026-12-05-table1-expected-improvement-predicted-optimum.md). One alternative per method, each carrying only its own settings: a count of
// candidates cannot exist beside a method that ignores it. `name` is the method's one spelling in
// a study file, the resolved study and the stored result.
struct LowestRunSelection {  // no final_selection, or candidates 0: the best single run is the answer
  static constexpr const char* name = "lowest_run";
};
struct ReplicateSelection {  // the best `candidates` runs, `replicates` nudged re-runs each
  static constexpr const char* name = "replicates";
  int candidates = 4;  // the best distinct runs re-run (1 to 20)
  int replicates = 3;  // nudged re-runs of each candidate (roundoff_replicates.hpp)
};
struct PredictedOptimumSelection {  // the verification run at the final predicted optimum
  static constexpr const char* name = "predicted_optimum";
};
using FinalSelectionSpec = std::variant<LowestRunSelection, ReplicateSelection, PredictedOptimumSelection>;

// A cheaper level of the study's own model ("cheap_level" in a study file; multi-fidelity): the
// same case with some settings changed (e.g. a drum at a larger coarse-graining factor with its
// time step), run `runs` times on a space-filling design over the whole box before iteration 0.
// The expected-improvement strategy then models the study's runs as rho x (kriging of the cheap
// runs) + a kriging correction (Kennedy & O'Hagan 2000; rbf_surrogate/multi_fidelity.hpp), so the
// cheap runs map the landscape and the study's runs correct it. The cheap runs never enter the
// answer, its posterior, its intervals or the warnings: those are the study model's alone.
struct CheapLevelSpec {
  // Merged (JSON merge patch, RFC 7386) into the model's overrides, or into every experiment's.
  nlohmann::json overrides = nlohmann::json::object();
  int runs = 0;  // runs of the cheap level (at least variables + 2)
};

struct StudySpec {
  int version = kStudyFormatVersion;
  std::string name;
  // Model: a case reference understood by cases::make_model ("pellet_compression",
  // "rotary_drum", "analytic" or a case JSON path) plus fixed case settings.
  std::string model_reference;
  nlohmann::json model_overrides = nlohmann::json::object();
  ParameterSet fixed_parameters;  // parameters held at given values (not varied)
  // Several experiments ("experiments" in the file): then model_reference is empty, the model
  // settings live in each experiment and every target names its experiment. Empty in the
  // single-model form ("model" + "targets"), which is one unnamed experiment.
  std::vector<ExperimentSpec> experiments;
  std::vector<VariableSpec> variables;
  std::vector<TargetSpec> targets;
  // Sampling.
  int points_per_iteration = 0;  // 0 before defaulting; parse fills ceil(1.5(n+1)+1)
  SamplingStrategy strategy = SamplingStrategy::srsm;
  // Domain reduction (docs/spec.md 3 / Stander & Craig 2002).
  double gamma_pan = 1.0;
  double gamma_osc = 0.6;
  double eta = 0.6;
  // Surrogate.
  std::string basis = "multiquadric";  // "multiquadric" or "gaussian"
  ResponseMode responses = ResponseMode::curve_points;
  double smoothing = 0.0;  // ridge term of the RBF fit (noisy responses)
  // Stopping.
  int max_iterations = 20;
  double design_tolerance = 0.01;     // change of the optimum, fraction of each range
  double objective_tolerance = 0.01;  // relative change of the optimum's objective
  // Budget caps the user sets (0 = none): the loop stops before an iteration that would pass
  // max_runs runs, or once max_wall_seconds [s] of this process's wall time have passed, and
  // says so in the stop reason (the verification, selection and interval-check runs come after).
  int max_runs = 0;
  double max_wall_seconds = 0.0;
  // The stable-answer rule (0 = off: the tolerance rule above alone decides). Largest relative gap
  // |f(run) - f_predicted| / f_predicted at which a run at the surrogate's predicted optimum agrees
  // with the prediction, and largest relative objective gain for which a move of the optimum counts
  // as no move. With it the loop stops once the run at the previous prediction agrees and the
  // optimum has stopped moving, and only when the verification run then agrees too; a verification
  // run outside it joins the data and the loop goes on while the iteration and run budgets last
  // (study_loop_stopping.hpp). sqrt(2/N) for N target points is the objective's own relative
  // noise (docs/study_format.md, "The loop").
  double verification_tolerance = 0.0;
  IntervalCheckSpec interval_check;
  FinalSelectionSpec final_selection;
  std::optional<CheapLevelSpec> cheap_level;  // none: one level (expected_improvement only)
  std::uint64_t seed = 1;
  std::filesystem::path base_dir;  // for relative paths (CSV files, case files)
};

// Parses a study JSON (strict). Relative paths resolve against base_dir. Throws
// std::runtime_error "study: <field>: <problem>; <fix>" on the first error.
StudySpec parse_study(const nlohmann::json& study, const std::filesystem::path& base_dir);
// Reads and parses a study file; base_dir = the file's folder.
StudySpec load_study_file(const std::filesystem::path& path);
// The resolved study as JSON (targets inline, defaults filled in). parse_study() of this
// gives back an equal spec; it is what the study store keeps and hashes.
nlohmann::json to_json(const StudySpec& spec);
// Stable 64-bit hash (FNV-1a of the resolved JSON text) identifying a study in its store.
std::uint64_t study_hash(const StudySpec& spec);

// The study of the cheap level: `spec` with cheap_level.overrides merged into its model overrides
// (every experiment's) and without a cheap level. Requires spec.cheap_level.
StudySpec cheap_level_study(const StudySpec& spec);

// Default points per iteration: 1.5(n+1)+1 rounded up (docs/spec.md 3; 16 for n = 9).
int default_points_per_iteration(int variables);

}  // namespace demfit::identify
