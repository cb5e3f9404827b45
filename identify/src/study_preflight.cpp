#include "demfit/identify/study_preflight.hpp"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <stdexcept>

#include "demfit/identify/model_fingerprint.hpp"
#include "demfit/identify/study_store.hpp"
#include "demfit/identify/units.hpp"
#include "demfit/imaging/profile_metrics.hpp"
#include "study_support.hpp"

namespace demfit::identify {
namespace {

std::string range_text(const std::vector<double>& x, const std::string& label) {
  const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
  char text[96];
  std::snprintf(text, sizeof text, "[%.6g, %.6g]", *lo, *hi);
  return text + (" " + label);
}

void convert(std::vector<double>& values, double factor) {
  if (factor != 1.0)
    for (double& v : values) v *= factor;
}

// Least-squares surface angle [deg] of a profile curve (x and z in one unit, so the slope is a ratio).
double surface_angle_deg(const Curve& curve) {
  imaging::SurfaceProfile profile;
  profile.x = curve.x;
  profile.z = curve.y;
  return imaging::fit_surface_line(profile).angle_deg;
}

// A bed in a turning drum is lifted on the side its wall moves up, so a photo and a model bed
// that slope opposite ways turn opposite ways (or the photo is mirrored): a fit would then trade
// friction for a flatter bed and report it with confidence. Beds flatter than this angle are
// not judged (a slow or slippery bed may be nearly level).
constexpr double kJudgedBedAngleDeg = 10.0;

void check_rotation_sense(const TargetSpec& t, const Curve& model_curve, const std::string& field) {
  if (!t.image || t.data.x.size() < 2 || model_curve.x.size() < 2) return;
  const double photo = surface_angle_deg(t.data), model = surface_angle_deg(model_curve);
  if (std::abs(photo) < kJudgedBedAngleDeg || std::abs(model) < kJudgedBedAngleDeg || (photo > 0.0) == (model > 0.0))
    return;
  char angles[96];
  std::snprintf(angles, sizeof angles, "slopes %.1f deg and the model's at the initial point %.1f deg", photo, model);
  throw std::runtime_error(field + ".image ('" + t.name + "'): the photo's surface " + angles +
                           " (negative = lifted on the left), so the model turns the other way; flip the sign of "
                           "the model's rotation (e.g. drum.rpm) or mirror the photo");
}

StudySpec checked_against(const StudySpec& spec, const Model& model,
                          const std::function<EvaluationOutcome(const ParameterSet&)>& evaluate,
                          std::optional<InitialRun>* initial) {
  detail::check_parameter_names(spec, model);  // names first: the evaluation would fail less clearly
  detail::check_declared_curves(spec, model);
  // The loop's run 0/0: the initial values through the unit coordinates (a log-scaled value may
  // differ from the written one in the last bit), so its outcome can stand for that run.
  const auto variables = detail::rbf_variables(spec);
  const ParameterSet parameters =
      detail::model_parameters(spec, model, variables, rbf_surrogate::to_unit(variables, detail::initial_values(spec)));
  EvaluationOutcome outcome;
  try {
    outcome = evaluate(parameters);
  } catch (const std::exception& e) {
    outcome.ok = false;
    outcome.error = e.what();
  }
  if (!outcome.ok)
    throw std::runtime_error("study: the model fails at the initial point of the variables: " + outcome.error);
  const CurveSet& curves = outcome.curves;
  StudySpec out = spec;
  for (std::size_t i = 0; i < out.targets.size(); ++i) {
    TargetSpec& t = out.targets[i];
    const std::string field = "study: targets[" + std::to_string(i) + "]";
    const auto found = curves.find(t.curve);
    if (found == curves.end()) {
      std::string known;
      for (const auto& [name, c] : curves) known += (known.empty() ? "" : ", ") + name;
      throw std::runtime_error(field + ".curve: '" + t.curve + "' is not a curve of model '" + spec.model_reference +
                               "'; it produces: " + known);
    }
    const Curve& m = found->second;
    convert(t.data.x, unit_factor(t.data.x_label, m.x_label, field + ".x_column"));
    convert(t.data.y, unit_factor(t.data.y_label, m.y_label, field + ".y_column"));
    if (column_unit(t.data.x_label).known && column_unit(m.x_label).known) t.data.x_label = m.x_label;
    if (column_unit(t.data.y_label).known && column_unit(m.y_label).known) t.data.y_label = m.y_label;
    if (m.x.empty())
      throw std::runtime_error(field + ".curve: the model's curve '" + t.curve + "' is empty at the initial point");
    const auto [tlo, thi] = std::minmax_element(t.data.x.begin(), t.data.x.end());
    const auto [mlo, mhi] = std::minmax_element(m.x.begin(), m.x.end());
    if (std::min(*thi, *mhi) <= std::max(*tlo, *mlo))
      throw std::runtime_error(field + ".x_column: the target's x " + range_text(t.data.x, t.data.x_label) +
                               " does not overlap the model's x at the initial point " + range_text(m.x, m.x_label) +
                               "; check the units and the fill (docs/study_format.md, \"Matching the fill\")");
    check_rotation_sense(t, m, field);
  }
  if (initial) *initial = InitialRun{parameters, outcome};
  return out;
}

// Bit for bit: ParameterSet's operator== takes -0.0 for 0.0.
bool same_bits(const ParameterSet& a, const ParameterSet& b) {
  return std::equal(a.begin(), a.end(), b.begin(), b.end(), [](const auto& x, const auto& y) {
    return x.first == y.first && std::bit_cast<std::uint64_t>(x.second) == std::bit_cast<std::uint64_t>(y.second);
  });
}

// On --resume, the store's run 0/0 when it is a successful initial-point run of the same simulation:
// the resolved model (case, overrides, external program) and the seed every evaluation receives
// (EvaluationContext::seed) as recorded in the store. nullopt otherwise; a store that cannot be read
// is left to the loop, whose opening of it says what is wrong.
std::optional<EvaluationRecord> stored_initial_run(const StudySpec& spec, const RunOptions& options) {
  const std::filesystem::path path = options.output_dir / "study.db";
  std::error_code error;
  if (!options.resume || options.resolved_model.is_null() || !std::filesystem::is_regular_file(path, error))
    return std::nullopt;
  try {
    const StudyStore store = StudyStore::open_existing(path);
    const EvaluationRecord* run = store.find_evaluation(0, 0);
    if (!run || !run->ok || run->kind != "initial") return std::nullopt;  // a failed run is evaluated again
    const std::optional<nlohmann::json> model = store.resolved_model();
    if (!model || !first_difference(*model, options.resolved_model).empty()) return std::nullopt;
    const nlohmann::json study = store.study_json();
    if (!study.contains("seed") || study.at("seed") != nlohmann::json(spec.seed)) return std::nullopt;
    return *run;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

}  // namespace

StudySpec preflight_study(const StudySpec& spec, const Model& model, const EvaluationContext& context,
                          std::optional<InitialRun>* initial) {
  return checked_against(
      spec, model,
      [&](const ParameterSet& p) {
        const auto start = std::chrono::steady_clock::now();
        EvaluationOutcome outcome;
        outcome.curves = model.evaluate(p, context);
        outcome.ok = true;
        outcome.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return outcome;
      },
      initial);
}

StudySpec preflight_study(const StudySpec& spec, const Model& model, Evaluator& evaluator,
                          std::optional<InitialRun>* initial) {
  return checked_against(
      spec, model, [&](const ParameterSet& p) { return evaluator.evaluate_points(model, {p}, nullptr).at(0); },
      initial);
}

StudySpec preflight_study(const StudySpec& spec, const Model& model, Evaluator& evaluator, RunOptions& options) {
  const std::optional<EvaluationRecord> stored = stored_initial_run(spec, options);
  bool reused = false;
  const StudySpec checked = checked_against(
      spec, model,
      [&](const ParameterSet& p) {
        if (!stored || !same_bits(stored->parameters, p)) return evaluator.evaluate_points(model, {p}, nullptr).at(0);
        reused = true;  // the model is deterministic: these are the curves it gives at p
        EvaluationOutcome outcome;
        outcome.ok = true;
        outcome.curves = stored->curves;
        outcome.wall_seconds = stored->wall_seconds;
        return outcome;
      },
      &options.initial_run);
  if (reused) options.initial_run.reset();  // the loop replays run 0/0 from the store
  return checked;
}

}  // namespace demfit::identify
