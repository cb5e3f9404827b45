// Strict study-file parsing (format: docs/study_format.md). Parse once at the door: JSON ->
// StudySpec, every problem reported as one line naming the field and the fix.
#include "demfit/identify/study_spec.hpp"

#include <cctype>
#include <cmath>
#include <fstream>
#include <set>
#include <stdexcept>

#include "demfit/identify/curve_io.hpp"
#include "demfit/identify/external_model.hpp"
#include "image_target.hpp"
#include "demfit/identify/json_document.hpp"
#include "demfit/identify/safe_output.hpp"
#include "cheap_level.hpp"
#include "json_reader.hpp"

namespace demfit::identify {
namespace {

using detail::JsonReader;

// Documented limits (docs/study_format.md).
constexpr int kMaxPointsPerIteration = 10000;
constexpr int kMaxIterations = 100000;
// Profile abscissae of an image target and points of a mapped curve: each costs memory and time
// per run; a few hundred describe any curve.
constexpr int kMaxProfilePoints = 100000;

VariableSpec parse_variable(const nlohmann::json& json, const std::string& path) {
  JsonReader in(json, path);
  VariableSpec v;
  v.name = in.text("name");
  v.lower = in.number("lower");
  v.upper = in.number("upper");
  v.initial = in.number_or("initial", 0.5 * (v.lower + v.upper));
  v.log_scale = in.boolean_or("log_scale", false);
  v.initial_range = in.number_or("initial_range", 1.0);
  in.finish();
  if (v.name.empty()) in.fail("name", "must not be empty");
  check_user_text("study: " + in.field("name"), v.name);
  if (!(v.upper > v.lower)) in.fail("upper", "must be greater than lower (" + std::to_string(v.lower) + ")");
  if (v.initial < v.lower || v.initial > v.upper) in.fail("initial", "must lie within [lower, upper]");
  if (v.log_scale && v.lower <= 0.0) in.fail("log_scale", "needs lower > 0; raise lower or set log_scale false");
  if (!(v.initial_range > 0.0 && v.initial_range <= 1.0))
    in.fail("initial_range", "must be in (0, 1] (fraction of upper - lower)");
  return v;
}

CurveMetric parse_metric(JsonReader& in) {
  const std::string name = in.text_or("metric", "mse");
  if (name == "mse") return CurveMetric::mse;
  if (name == "curve_mapping") return CurveMetric::curve_mapping;
  if (name == "profile_area") return CurveMetric::profile_area;
  in.fail("metric", "'" + name + "' is not a metric; use \"mse\", \"curve_mapping\" or \"profile_area\"");
}

std::vector<double> number_array(JsonReader& in, const std::string& key) {
  const auto& value = in.raw(key);
  if (!value.is_array()) in.fail(key, "expected an array of numbers");
  std::vector<double> out;
  for (const auto& item : value) {
    if (!item.is_number()) in.fail(key, "expected only numbers, got " + json_excerpt(item));
    out.push_back(item.get<double>());
  }
  return out;
}

ImageTargetSpec parse_image_target(JsonReader& in) {
  ImageTargetSpec image;
  image.file = in.text("image");
  image.diameter = in.number("image_diameter");
  image.threshold = in.number_or("image_threshold", image.threshold);
  const std::string material = in.text_or("image_material", "dark");
  image.margin = in.number_or("image_margin", image.margin);
  image.points = in.integer_or("image_points", image.points);
  if (!(image.diameter > 0.0)) in.fail("image_diameter", "must be > 0 (inner drum diameter in metres, e.g. 0.084)");
  if (image.threshold > 1.0) in.fail("image_threshold", "must be a grey level in [0, 1], or -1 for automatic (Otsu)");
  if (material != "dark" && material != "light")
    in.fail("image_material",
            "'" + material + "' is unknown; use \"dark\" (powder darker than the background) or \"light\"");
  image.material_is_dark = material == "dark";
  if (!(image.margin >= 0.0 && image.margin < 1.0))
    in.fail("image_margin", "must be in [0, 1) (fraction of the drum radius)");
  if (image.points < 2 || image.points > kMaxProfilePoints)
    in.fail("image_points", "must be 2 to " + std::to_string(kMaxProfilePoints));
  return image;
}

TargetSpec parse_target(const nlohmann::json& json, const std::string& path, std::size_t index,
                        const std::filesystem::path& base_dir) {
  JsonReader in(json, path);
  TargetSpec t;
  t.curve = in.text("curve");
  t.name = in.text_or("name", t.curve.empty() ? "target" + std::to_string(index) : t.curve);
  const bool has_image = in.has("image");
  const bool has_csv = in.has("csv");
  if (has_image) {
    if (has_csv || in.has("x") || in.has("y") || in.has("x_column") || in.has("y_column"))
      in.fail("image",
              "an image target takes its points from the photo (columns x_mm, z_mm); leave out csv, x, y, "
              "x_column and y_column");
    t.image = parse_image_target(in);
    try {
      t.data = detail::read_image_target(*t.image, base_dir);
    } catch (const std::exception& e) { in.fail("image", e.what()); }
  } else {
    const std::string x_column = in.text("x_column");
    const std::string y_column = in.text("y_column");
    const bool has_inline = in.has("x") || in.has("y");
    if (has_csv == has_inline)
      in.fail("csv", "give either \"csv\" (file path), inline \"x\" and \"y\" arrays, or \"image\" (drum photo)");
    if (has_csv) {
      t.csv = in.text("csv");
      const auto resolved = t.csv.is_absolute() ? t.csv : base_dir / t.csv;
      t.data = read_curve_csv(resolved, x_column, y_column);
    } else {
      t.data = Curve{x_column, y_column, number_array(in, "x"), number_array(in, "y")};
      if (t.data.x.size() != t.data.y.size()) in.fail("y", "must have as many values as x");
      if (t.data.x.size() < 2) in.fail("x", "a target needs at least 2 points");
    }
  }
  in.text_or("source", "");  // informational (where inline data came from)
  // Names reach file names, plots and reports: printable text only.
  check_user_text("study: " + in.field("curve"), t.curve);
  check_user_text("study: " + in.field("name"), t.name);
  t.metric = parse_metric(in);
  t.weight = in.number_or("weight", 1.0);
  t.scale = in.number_or("scale", 0.0);
  t.mapping_points = in.integer_or("mapping_points", 0);
  in.finish();
  for (std::size_t i = 0; i < t.data.x.size(); ++i)
    if (!std::isfinite(t.data.x[i]) || !std::isfinite(t.data.y[i]))
      in.fail(has_csv ? "csv" : has_image ? "image" : "x", "point " + std::to_string(i) + " is not finite");
  if (t.metric == CurveMetric::profile_area)
    for (std::size_t i = 1; i < t.data.x.size(); ++i)
      if (!(t.data.x[i] > t.data.x[i - 1]))
        in.fail("metric", "profile_area compares profiles z(x) and needs the target's x increasing (point " +
                              std::to_string(i) + " is not)");
  if (!(t.weight > 0.0)) in.fail("weight", "must be > 0");
  if (t.scale < 0.0) in.fail("scale", "must be >= 0 (0 = max|y| of the target)");
  if (t.mapping_points < 0 || t.mapping_points == 1 || t.mapping_points > kMaxProfilePoints)
    in.fail("mapping_points", "must be 0 (auto) or 2 to " + std::to_string(kMaxProfilePoints));
  return t;
}

// The "model" object: case reference, fixed case settings, fixed model parameters.
// Or, instead of "case" and "overrides", "external": an external program (external_model.hpp), kept
// as reference "external" with the checked "external" object as its overrides.
void parse_model(JsonReader in, std::string& reference, nlohmann::json& overrides, ParameterSet& fixed_parameters) {
  if (in.has("external")) {
    if (in.has("case") || in.has("overrides"))
      in.fail("external", "give either \"case\" (a demfit case) or \"external\" (a program), not both");
    reference = kExternalModelReference;
    overrides = to_json(parse_external_spec(in.raw("external"), in.field("external")));
  } else {
    reference = in.text("case");
    if (reference == kExternalModelReference)
      in.fail("case", "'external' is not a case; describe an external program as \"external\": {...} "
                      "(docs/external-model.md)");
  }
  if (in.has("overrides")) {
    const auto& given = in.raw("overrides");
    if (!given.is_object()) in.fail("overrides", "expected a JSON object of case settings");
    overrides = given;
  }
  if (in.has("fixed_parameters")) {
    JsonReader fixed = in.object("fixed_parameters");
    for (const auto& item : in.raw("fixed_parameters").items()) fixed_parameters[item.key()] = fixed.number(item.key());
    fixed.finish();
  }
  in.finish();
  if (reference.empty()) in.fail("case", "must not be empty");
}

// "targets" of the study or of one experiment (names unique within that list).
void parse_targets(JsonReader& in, const std::string& path, const std::filesystem::path& base_dir,
                   std::vector<TargetSpec>& out) {
  const auto& targets = in.raw("targets");
  if (!targets.is_array() || targets.empty()) in.fail("targets", "expected a non-empty array of targets");
  std::set<std::string> names;
  for (std::size_t i = 0; i < targets.size(); ++i) {
    out.push_back(parse_target(targets[i], path + "targets[" + std::to_string(i) + "]", i, base_dir));
    if (!names.insert(safe_slug(out.back().name)).second)
      in.fail("targets",
              "two targets are named '" + out.back().name + "' (or alike in file names); give each a unique \"name\"");
  }
}

bool valid_experiment_name(const std::string& name) {
  if (name.empty()) return false;
  for (char c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-')) return false;
  return true;
}

// "experiments": [{"name", "model", "targets"}]. Targets are qualified by their experiment
// (study_spec.hpp: name "<experiment>.<target>", curve "<experiment>/<curve>").
void parse_experiments(JsonReader& study, StudySpec& spec) {
  const auto& experiments = study.raw("experiments");
  if (!experiments.is_array() || experiments.empty())
    study.fail("experiments", "expected a non-empty array of experiments ({\"name\", \"model\", \"targets\"})");
  std::set<std::string> names;
  for (std::size_t e = 0; e < experiments.size(); ++e) {
    const std::string path = "experiments[" + std::to_string(e) + "]";
    JsonReader in(experiments[e], path);
    ExperimentSpec experiment;
    experiment.name = in.text("name");
    if (!valid_experiment_name(experiment.name))
      in.fail("name", "'" + experiment.name + "' must be non-empty letters, digits, '_' or '-' (it names files)");
    if (!names.insert(experiment.name).second)
      in.fail("name", "two experiments are named '" + experiment.name + "'; give each a unique name");
    parse_model(in.object("model"), experiment.model_reference, experiment.model_overrides,
                experiment.fixed_parameters);
    std::vector<TargetSpec> targets;
    parse_targets(in, path + ".", spec.base_dir, targets);
    in.finish();
    for (TargetSpec& t : targets) {
      t.experiment = experiment.name;
      t.name = experiment.name + "." + t.name;
      t.curve = experiment.name + "/" + t.curve;
      spec.targets.push_back(std::move(t));
    }
    spec.experiments.push_back(std::move(experiment));
  }
}

void parse_sampling(JsonReader in, StudySpec& spec) {
  spec.points_per_iteration = in.integer_or("points_per_iteration", 0);
  const std::string strategy = in.text_or("strategy", "srsm");
  if (strategy == "srsm")
    spec.strategy = SamplingStrategy::srsm;
  else if (strategy == "adaptive_infill")
    spec.strategy = SamplingStrategy::adaptive_infill;
  else if (strategy == "expected_improvement")
    spec.strategy = SamplingStrategy::expected_improvement;
  else
    in.fail("strategy", "'" + strategy + "' is unknown; use \"srsm\", \"adaptive_infill\" or \"expected_improvement\"");
  in.finish();
  if (spec.points_per_iteration < 0) in.fail("points_per_iteration", "must be >= 0 (0 = default 1.5(n+1)+1)");
  // Each point is one simulation run; a huge design is a typo (10^9 once ended in std::bad_alloc).
  if (spec.points_per_iteration > kMaxPointsPerIteration)
    in.fail("points_per_iteration", "must be <= " + std::to_string(kMaxPointsPerIteration) + " (runs per iteration)");
}

void parse_domain_reduction(JsonReader in, StudySpec& spec) {
  spec.gamma_pan = in.number_or("gamma_pan", spec.gamma_pan);
  spec.gamma_osc = in.number_or("gamma_osc", spec.gamma_osc);
  spec.eta = in.number_or("eta", spec.eta);
  in.finish();
  if (!(spec.gamma_pan > 0.0 && spec.gamma_pan <= 1.5)) in.fail("gamma_pan", "must be in (0, 1.5]");
  if (!(spec.gamma_osc > 0.0 && spec.gamma_osc <= 1.0)) in.fail("gamma_osc", "must be in (0, 1]");
  if (!(spec.eta > 0.0 && spec.eta <= 1.0)) in.fail("eta", "must be in (0, 1]");
  if (spec.gamma_pan < spec.gamma_osc) in.fail("gamma_pan", "must be >= gamma_osc");
}

void parse_surrogate(JsonReader in, StudySpec& spec) {
  spec.basis = in.text_or("basis", spec.basis);
  const std::string responses = in.text_or("responses", "curve_points");
  spec.smoothing = in.number_or("smoothing", 0.0);
  in.finish();
  if (spec.basis != "multiquadric" && spec.basis != "gaussian")
    in.fail("basis", "'" + spec.basis + "' is unknown; use \"multiquadric\" or \"gaussian\"");
  if (responses == "curve_points")
    spec.responses = ResponseMode::curve_points;
  else if (responses == "principal_components")
    spec.responses = ResponseMode::principal_components;
  else
    in.fail("responses", "'" + responses + "' is unknown; use \"curve_points\" or \"principal_components\"");
  if (spec.smoothing < 0.0) in.fail("smoothing", "must be >= 0");
}

void parse_stopping(JsonReader in, StudySpec& spec) {
  spec.max_iterations = in.integer_or("max_iterations", spec.max_iterations);
  spec.design_tolerance = in.number_or("design_tolerance", spec.design_tolerance);
  spec.objective_tolerance = in.number_or("objective_tolerance", spec.objective_tolerance);
  spec.max_runs = in.integer_or("max_runs", spec.max_runs);
  spec.max_wall_seconds = in.number_or("max_wall_seconds", spec.max_wall_seconds);
  spec.verification_tolerance = in.number_or("verification_tolerance", spec.verification_tolerance);
  in.finish();
  if (!(spec.verification_tolerance >= 0.0) || !(spec.verification_tolerance <= 10.0))
    in.fail("verification_tolerance",
            "must be 0 (off) to 10 (a relative objective gap; sqrt(2/N) for N target points is the noise)");
  if (spec.max_runs < 0 || spec.max_runs > 1000000)
    in.fail("max_runs", "must be 0 (no cap) to 1000000 runs");
  if (!(spec.max_wall_seconds >= 0.0) || !std::isfinite(spec.max_wall_seconds))
    in.fail("max_wall_seconds", "must be 0 (no cap) or a finite number of seconds");
  if (spec.max_iterations < 1) in.fail("max_iterations", "must be >= 1");
  if (spec.max_iterations > kMaxIterations) in.fail("max_iterations", "must be <= " + std::to_string(kMaxIterations));
  if (!(spec.design_tolerance >= 0.0)) in.fail("design_tolerance", "must be >= 0");
  if (!(spec.objective_tolerance >= 0.0)) in.fail("objective_tolerance", "must be >= 0");
}

void parse_interval_check(JsonReader in, StudySpec& spec) {
  IntervalCheckSpec& check = spec.interval_check;
  check.max_steps = in.integer_or("max_steps", 6);
  check.replicates = in.integer_or("replicates", check.replicates);
  check.first_step = in.number_or("first_step", check.first_step);
  check.all_variables = in.boolean_or("all_variables", check.all_variables);
  in.finish();
  if (check.max_steps < 0 || check.max_steps > 20) in.fail("max_steps", "must be 0 (no check) to 20");
  if (check.replicates < 1 || check.replicates > kMaxReplicates)
    in.fail("replicates", "must be 1 to " + std::to_string(kMaxReplicates));
  if (!(check.first_step > 0.0 && check.first_step <= 0.5))
    in.fail("first_step", "must be in (0, 0.5] (a fraction of each variable's range)");
}

void parse_final_selection(JsonReader in, StudySpec& spec) {
  const std::string method = in.text_or("method", ReplicateSelection::name);
  if (method == LowestRunSelection::name || method == PredictedOptimumSelection::name) {
    for (const char* key : {"candidates", "replicates"})
      if (in.has(key)) in.fail(key, "belongs to method 'replicates'; remove it or set method to 'replicates'");
    in.finish();
    if (method == LowestRunSelection::name)
      spec.final_selection = LowestRunSelection{};
    else
      spec.final_selection = PredictedOptimumSelection{};
    return;
  }
  if (method != ReplicateSelection::name)
    in.fail("method", std::string("must be '") + ReplicateSelection::name + "', '" + PredictedOptimumSelection::name +
                          "' or '" + LowestRunSelection::name + "', not '" + method + "'");
  ReplicateSelection selection;
  selection.candidates = in.integer_or("candidates", selection.candidates);
  selection.replicates = in.integer_or("replicates", selection.replicates);
  in.finish();
  if (selection.candidates < 0 || selection.candidates > 20)
    in.fail("candidates", "must be 0 (off: the best single run is the answer) to 20");
  if (selection.replicates < 1 || selection.replicates > kMaxReplicates)
    in.fail("replicates", "must be 1 to " + std::to_string(kMaxReplicates));
  if (selection.candidates == 0)
    spec.final_selection = LowestRunSelection{};
  else
    spec.final_selection = selection;
}

}  // namespace

int default_points_per_iteration(int variables) {
  return static_cast<int>(std::ceil(1.5 * (variables + 1) + 1.0 - 1e-12));
}

StudySpec parse_study(const nlohmann::json& study, const std::filesystem::path& base_dir) {
  JsonReader in(study, "");
  StudySpec spec;
  spec.base_dir = base_dir;
  if (!in.has("demfit_study_version")) in.fail("demfit_study_version", "missing; add \"demfit_study_version\": 1");
  spec.version = in.integer_or("demfit_study_version", 0);
  if (spec.version != kStudyFormatVersion)
    in.fail("demfit_study_version", "version " + std::to_string(spec.version) +
                                        " is not supported; this demfit reads version " +
                                        std::to_string(kStudyFormatVersion));
  spec.name = in.text_or("name", "study");
  check_user_text("study: name", spec.name);
  const bool experiments = in.has("experiments");
  if (experiments && (in.has("model") || in.has("targets")))
    in.fail("experiments", "give either \"experiments\" or a top-level \"model\" and \"targets\", not both");
  if (experiments)
    parse_experiments(in, spec);
  else
    parse_model(in.object("model"), spec.model_reference, spec.model_overrides, spec.fixed_parameters);
  const auto& variables = in.raw("variables");
  if (!variables.is_array() || variables.empty()) in.fail("variables", "expected a non-empty array of variables");
  std::set<std::string> names;
  for (std::size_t i = 0; i < variables.size(); ++i) {
    spec.variables.push_back(parse_variable(variables[i], "variables[" + std::to_string(i) + "]"));
    const std::string& name = spec.variables.back().name;
    if (!names.insert(name).second) in.fail("variables", "'" + name + "' appears twice; names must be unique");
    if (spec.fixed_parameters.count(name))
      in.fail("variables", "'" + name + "' is also in model.fixed_parameters; keep one");
    for (const auto& experiment : spec.experiments)
      if (experiment.fixed_parameters.count(name))
        in.fail("variables",
                "'" + name + "' is also in the fixed_parameters of experiment '" + experiment.name + "'; keep one");
  }
  if (!experiments) parse_targets(in, "", base_dir, spec.targets);
  if (in.has("sampling")) parse_sampling(in.object("sampling"), spec);
  if (in.has("domain_reduction")) parse_domain_reduction(in.object("domain_reduction"), spec);
  if (in.has("surrogate")) parse_surrogate(in.object("surrogate"), spec);
  if (in.has("stopping")) parse_stopping(in.object("stopping"), spec);
  if (in.has("interval_check")) parse_interval_check(in.object("interval_check"), spec);
  if (in.has("final_selection")) parse_final_selection(in.object("final_selection"), spec);
  if (in.has("cheap_level")) detail::parse_cheap_level(in.object("cheap_level"), spec);
  if (in.has("seed")) {
    const auto& seed = in.raw("seed");
    if (!seed.is_number_unsigned() && !(seed.is_number_integer() && seed.get<long long>() >= 0))
      in.fail("seed", "expected a non-negative integer");
    spec.seed = seed.get<std::uint64_t>();
  }
  in.finish();
  if (spec.points_per_iteration == 0)
    spec.points_per_iteration = default_points_per_iteration(static_cast<int>(spec.variables.size()));
  if (spec.points_per_iteration < 2) in.fail("sampling", "points_per_iteration must be >= 2");
  detail::check_cheap_level(in, spec);
  return spec;
}

StudySpec load_study_file(const std::filesystem::path& path) {
  // Size, nesting depth and duplicate keys are checked while reading (json_document.hpp).
  const nlohmann::json json = read_json_file(path, "study file");
  return parse_study(json, std::filesystem::absolute(path).parent_path());
}

}  // namespace demfit::identify
