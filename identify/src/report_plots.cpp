#include "report_plots.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "demfit/identify/gnuplot.hpp"
#include "demfit/identify/objective.hpp"
#include "demfit/identify/reported_interval.hpp"
#include "demfit/identify/safe_output.hpp"
#include "demfit/identify/study_warnings.hpp"
#include "target_misfit.hpp"
#include "study_support.hpp"

namespace demfit::identify::detail {

std::pair<std::vector<double>, std::vector<double>> region_band(const std::vector<rbf_surrogate::Variable>& variables,
                                                                const IterationRecord& iteration) {
  const int n = static_cast<int>(variables.size());
  Eigen::VectorXd lower(n), upper(n);
  for (int j = 0; j < n; ++j) {
    lower(j) = std::clamp(iteration.region_center[j] - 0.5 * iteration.region_range[j], 0.0, 1.0);
    upper(j) = std::clamp(iteration.region_center[j] + 0.5 * iteration.region_range[j], 0.0, 1.0);
  }
  return {to_std(rbf_surrogate::from_unit(variables, lower)), to_std(rbf_surrogate::from_unit(variables, upper))};
}

std::pair<std::vector<std::string>, std::string> write_plots(const StudySpec& spec,
                                                             const std::vector<EvaluationRecord>& runs,
                                                             const std::vector<IterationRecord>& iterations,
                                                             const EvaluationRecord* best,
                                                             const std::filesystem::path& output_dir) {
  std::vector<std::string> images;
  std::string warning;
  auto plot = [&](const std::string& name, const std::string& commands) {
    const std::string problem = gnuplot_png(output_dir / name, commands);
    if (problem.empty())
      images.push_back(name);
    else if (warning.empty())
      warning = problem;
  };
  const std::string csv_setup = "set datafile separator ','\nset key autotitle columnhead\n";
  // gnuplot runs inside output_dir: data files are named relative to it (slugs, never a path).
  auto file = [&](const std::string& name) { return gnuplot_quote(safe_slug(name)); };
  if (best) {
    for (const auto& t : spec.targets) {
      if (!best->curves.count(t.curve)) continue;
      plot(safe_slug("target_" + t.name + ".png"),
           csv_setup + "set title " +
               gnuplot_quote("target '" + t.name + "' vs best run (objective " + format_number(best->objective) + ")") +
               "\nset xlabel " + gnuplot_quote(t.data.x_label) + "\nset ylabel " + gnuplot_quote(t.data.y_label) +
               "\nplot " + file("target_" + t.name + ".csv") + " using 1:2 with points pt 7 ps 0.6 title 'target', " +
               file("best_" + t.name + ".csv") + " using 1:2 with lines lw 2 title 'best run'");
    }
  }
  bool positive = false;
  for (const auto& r : runs) positive = positive || (r.ok && r.objective > 0.0);
  if (!runs.empty()) {
    plot("objective_history.png", csv_setup +
                                      "set title 'objective per run and best per iteration'\nset xlabel 'iteration'\n"
                                      "set ylabel 'composite objective (-)'\n" +
                                      (positive ? "set logscale y\n" : "") + "plot " + file("evaluations.csv") +
                                      " using 1:5 with points pt 6 title 'evaluated runs', " + file("iterations.csv") +
                                      " using 1:3 with linespoints lw 2 title 'best so far', " +
                                      file("iterations.csv") +
                                      " using 1:4 with linespoints dt 2 title 'predicted optimum'");
  }
  if (!iterations.empty()) {
    for (std::size_t j = 0; j < spec.variables.size(); ++j) {
      const auto& v = spec.variables[j];
      const int optimum = 7 + 3 * static_cast<int>(j);
      plot(safe_slug("variable_" + v.name + ".png"),
           csv_setup + "set title " + gnuplot_quote("variable " + v.name + ": predicted optimum and subregion") +
               "\nset xlabel 'iteration'\nset ylabel " + gnuplot_quote(v.name) + "\n" +
               (v.log_scale ? "set logscale y\n" : "") + "set style fill transparent solid 0.25 noborder\nplot " +
               file("iterations.csv") + " using 1:" + std::to_string(optimum + 1) + ":" + std::to_string(optimum + 2) +
               " with filledcurves title 'subregion', " + file("iterations.csv") +
               " using 1:" + std::to_string(optimum) + " with linespoints lw 2 title 'predicted optimum', " +
               file("evaluations.csv") + " using 1:" + std::to_string(7 + j) + " with points pt 1 title 'runs'");
    }
  }
  return {images, warning};
}

namespace {

std::string number_or_dash(const nlohmann::json& value) {
  return value.is_number() ? format_number(value.get<double>()) : "-";
}

}  // namespace

namespace {

// The interval-end checks (interval_check.hpp) behind the reported intervals, when the study ran them.
void interval_check_section(std::ostringstream& md, const StudySpec& spec, const nlohmann::json& uncertainty) {
  const nlohmann::json posterior = uncertainty.value("posterior", nlohmann::json());
  if (!posterior.is_object() || !posterior.contains("interval_check")) return;
  const nlohmann::json& check = posterior["interval_check"];
  md << "\nInterval-end checks (" << check.value("runs", 0) << " runs after the loop; docs/study_format.md), "
     << check.value("method", std::string("method not stored")) << ". Threshold " << number_or_dash(check["threshold"])
     << ": the largest objective of the best run, its nudged replicates and the runs next to it.\n\n"
        "| variable | sampled interval | checked interval | check runs (value: objective, fits?) "
        "|\n|---|---|---|---|\n";
  for (const auto& v : spec.variables) {
    const nlohmann::json& ends = check["variables"][v.name];
    const nlohmann::json& entry = posterior["variables"][v.name];
    md << "| " << v.name << " | [" << number_or_dash(entry.value("sampled_lower_95", nlohmann::json())) << ", "
       << number_or_dash(entry.value("sampled_upper_95", nlohmann::json())) << "] | ";
    if (!ends["lower"].value("checked", false)) {
      md << "not checked (within the fitted runs) | - |\n";
      continue;
    }
    md << "[" << number_or_dash(ends["lower"]["end"]) << ", " << number_or_dash(ends["upper"]["end"]) << "] |";
    for (const char* side : {"lower", "upper"})
      for (const auto& c : ends[side]["checks"])
        md << " " << number_or_dash(c["value"]) << ": " << number_or_dash(c["objective"])
           << (c.value("fits", false) ? " yes;" : " no;");
    md << " |\n";
  }
}

void variables_section(std::ostringstream& md, const StudySpec& spec, const EvaluationRecord& best,
                       const nlohmann::json& uncertainty) {
  md << "## Identified variables\n\n"
     << "| variable | initial | identified | 95 % interval | bounds | identifiable |\n|---|---|---|---|---|---|\n";
  for (const auto& v : spec.variables) {
    std::string ci = "-", identifiable = "-";
    if (uncertainty.is_object()) {
      const ReportedInterval interval = reported_interval(uncertainty, v.name, best.parameters.at(v.name));
      ci = interval_text(interval);
      identifiable = interval.identifiable ? "yes" : "**no**";
    }
    md << "| " << v.name << " | " << format_number(v.initial) << " | " << format_number(best.parameters.at(v.name))
       << " | " << ci << " | [" << format_number(v.lower) << ", " << format_number(v.upper) << "]"
       << (v.log_scale ? " log" : "") << " | " << identifiable << " |\n";
  }
  if (!uncertainty.is_object()) return;
  md << "\nThe 95 % interval is the marginal of the posterior (Gibbs sampling on the local linear surrogate of "
        "the residuals, noise level estimated from the runs), the same in `best_parameters.json` and the LS-DYNA "
        "export; it stays right when another variable is poorly pinned. \"(linearised)\" marks a value ± "
        "half-width, used only when the posterior could not be computed.\n";
  interval_check_section(md, spec, uncertainty);
  if (uncertainty.value("jacobian", std::string()) == "regression") {
    md << "\nFor comparison, the linearised half-widths (conditional on the other variables; "
          "`linearised_ci95_half_width` in best_parameters.json) use Cov = s² (JᵀJ)⁻¹. J is the slope of a linear "
          "regression of the "
          "evaluated residual vectors on the variables over the "
       << uncertainty["runs_used"] << " runs nearest the optimum; s² = residual variance at the best run ("
       << uncertainty["degrees_of_freedom"] << " degrees of freedom) plus the regression's scatter (simulation noise, "
       << number_or_dash(uncertainty["simulation_noise_variance"])
       << " per residual). A variable is not identifiable when its interval exceeds half its bounds or its effect "
          "on the curve is below twice that noise (effect/noise:";
    for (const auto& v : spec.variables)
      md << " " << v.name << " " << number_or_dash(uncertainty["effect_significance"].value(v.name, nlohmann::json()));
    md << "). Correlation matrix:\n\n| |";
  } else {
    md << "\nFor comparison, linearised half-widths (Cov = s² (JᵀJ)⁻¹, J = Jacobian of the residual vector at "
          "the best run, s² = residual variance, "
       << uncertainty["degrees_of_freedom"] << " degrees of freedom). Correlation matrix:\n\n| |";
  }
  for (const auto& v : spec.variables) md << " " << v.name << " |";
  md << "\n|---|";
  for (std::size_t j = 0; j < spec.variables.size(); ++j) md << "---|";
  md << "\n";
  for (std::size_t i = 0; i < spec.variables.size(); ++i) {
    md << "| " << spec.variables[i].name << " |";
    for (std::size_t j = 0; j < spec.variables.size(); ++j)
      md << " " << number_or_dash(uncertainty["correlation"][i][j]) << " |";
    md << "\n";
  }
}

const char* metric_label(CurveMetric metric) {
  switch (metric) {
    case CurveMetric::mse:
      return "MSE";
    case CurveMetric::curve_mapping:
      return "curve mapping";
    case CurveMetric::profile_area:
      return "profile area";
  }
  return "?";
}

// "- model: `case`" or, with several experiments, one line per experiment with its settings.
std::string model_lines(const StudySpec& spec) {
  // Paths and texts from the inputs are echoed through printable(): no control or bidirectional
  // character of a received study can forge a line of the report.
  if (spec.experiments.empty()) return "- model: `" + printable(spec.model_reference) + "`\n";
  std::string out = "- experiments (each design point runs all of them; resolved study: `study_resolved.json`):\n";
  for (const auto& e : spec.experiments)
    out += "  - `" + printable(e.name) + "`: case `" + printable(e.model_reference) + "`, overrides `" +
           printable(e.model_overrides.dump()) +
           "`, fixed parameters `" + nlohmann::json(e.fixed_parameters).dump() + "`\n";
  return out;
}

// Per target (grouped by experiment): its term of the objective and the best run's misfit in the
// curve's units (RMS; differing area for profile targets), so results compare with other sources.
void targets_section(std::ostringstream& md, const StudySpec& spec, const EvaluationRecord& best) {
  const CompositeObjective objective(spec.targets);
  std::vector<double> terms(spec.targets.size(), std::nan(""));
  try {
    terms = objective.target_objectives(objective.responses(best.curves));
  } catch (const std::exception&) {}
  const auto misfits = target_misfits(spec.targets, best.curves);
  md << "\n## Targets (best run)\n\n| experiment | target | simulated curve | points | metric | weight | objective "
        "term "
        "| RMS misfit | differing area |\n|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& experiment : experiment_names(spec)) {
    for (std::size_t t = 0; t < spec.targets.size(); ++t) {
      const TargetSpec& target = spec.targets[t];
      if (target.experiment != experiment) continue;
      const auto& m = misfits[t];
      const std::string y_unit = " (" + target.data.y_label + ")";
      md << "| " << (experiment.empty() ? "-" : experiment) << " | `" << target.name << "` | `" << target.curve
         << "` | " << target.data.x.size() << " | " << metric_label(target.metric) << " | "
         << format_number(target.weight) << " | " << format_number(terms[t]) << " | "
         << (m.available ? format_number(m.rms) + y_unit : "-") << " | "
         << (m.available && m.area >= 0.0
                 ? format_number(m.area) + " (" + target.data.x_label + " × " + target.data.y_label + ")"
                 : "-")
         << " |\n";
    }
  }
  md << "\nRMS misfit: mse targets at the target's points; curve mapping: y-distance of the matched stations; "
        "profile targets: over the common x-range of the two profiles (exact for piecewise linear profiles), "
        "with the area between them (the source's differing-area metric).\n";
}

void failures_and_files_section(std::ostringstream& md, const std::vector<EvaluationRecord>& runs, int failed) {
  if (failed) {
    md << "## Failed runs\n\n| iteration/point | error |\n|---|---|\n";
    int listed = 0;
    for (const auto& r : runs)
      if (!r.ok && listed++ < 30) md << "| " << r.iteration << "/" << r.point << " | " << printable(r.error) << " |\n";
    md << "\n";
  }
  md << "## Files\n\n- `report.html`: this report in one self-contained page, plots embedded\n"
        "- `study_resolved.json`: the study as run (targets inline, defaults filled in)\n"
        "- `best_parameters.json`: identified values, all model parameters of the best run, intervals\n"
        "- `evaluations.csv`, `iterations.csv`: histories (variables in model units)\n"
        "- `target_<name>.csv`, `best_<name>.csv`: target and best simulated curves\n"
        "- `study.db`: the study store (`demfit report study.db` rebuilds these files, "
        "`demfit export study.db --lsdyna out.k` writes LS-DYNA cards)\n";
}

// The answer at the predicted optimum, or why the best run stayed the answer.
std::string predicted_optimum_line(const nlohmann::json& s) {
  const nlohmann::json& lowest = s.at("best_run");
  std::ostringstream line;
  if (s.contains("fallback")) {
    line << "- final selection at the predicted optimum not made: " << s.at("fallback").get<std::string>() << "\n";
  } else {
    line << "- the verification run " << s.at("iteration").get<int>() << "/" << s.at("point").get<int>()
         << " at the surrogate's final predicted optimum is the answer (final selection `predicted_optimum`); "
         << "the lowest single run, " << lowest.at("iteration").get<int>() << "/" << lowest.at("point").get<int>()
         << ", had " << format_number(lowest.at("objective").get<double>()) << "\n";
    if (s.contains("note")) line << "- answer rule: " << s.at("note").get<std::string>() << "\n";
  }
  return line.str();
}

// The final selection's choice (final_selection.hpp), when the study made one.
std::string selection_line(const std::optional<nlohmann::json>& result) {
  if (!result || !result->contains("final_selection") || !(*result)["final_selection"].is_object()) return "";
  const nlohmann::json& s = (*result)["final_selection"];
  if (s.value("method", "") == PredictedOptimumSelection::name) return predicted_optimum_line(s);
  const nlohmann::json& candidates = s.at("candidates");
  const nlohmann::json& chosen = candidates.at(s.at("chosen").get<std::size_t>());
  const nlohmann::json& lowest = candidates.at(0);
  std::ostringstream line;
  line << "- chosen by final selection among the " << candidates.size() << " best runs, each re-run "
       << s.at("replicates").get<int>() << " times as round-off replicates: mean objective "
       << format_number(chosen.at("mean_objective").get<double>()) << "; the lowest single run, "
       << lowest.at("iteration").get<int>() << "/" << lowest.at("point").get<int>() << " ("
       << format_number(lowest.at("objective").get<double>()) << "), averages "
       << format_number(lowest.at("mean_objective").get<double>()) << "\n";
  return line.str();
}

}  // namespace

std::string study_status(const std::optional<nlohmann::json>& result) {
  if (!result) return "NOT finished (report built from the runs stored so far)";
  if (result->contains("stop_reason")) return "finished, " + result->value("stop_reason", std::string());
  return result->value("converged", false) ? "finished, converged (design and objective change below tolerance)"
                                           : "finished, iteration limit reached";
}

// The cheap level (study_spec.hpp CheapLevelSpec): what it changed and what its runs cost.
std::string cheap_level_line(const StudySpec& spec, const std::optional<nlohmann::json>& result) {
  std::string line = "- cheap level (mapped the landscape for expected improvement; not part of the answer): " +
                     spec.cheap_level->overrides.dump() + ", " + std::to_string(spec.cheap_level->runs) + " runs";
  const nlohmann::json summary = result ? result->value("cheap_level", nlohmann::json()) : nlohmann::json();
  if (summary.is_object())
    line += " (" + std::to_string(summary.value("failed_runs", 0)) + " failed), " +
            format_number(summary.value("run_wall_seconds", 0.0)) + " s of run time";
  return line + "\n";
}

std::string report_markdown(const StudySpec& spec, const std::vector<EvaluationRecord>& runs,
                            const std::vector<IterationRecord>& iterations, const EvaluationRecord* best,
                            const std::optional<nlohmann::json>& result, const std::vector<std::string>& images) {
  std::ostringstream md;
  int failed = 0;
  for (const auto& r : runs) failed += r.ok ? 0 : 1;
  md << "# demfit identification report: " << spec.name << "\n\n"
     << model_lines(spec) << "- status: " << study_status(result) << "\n- runs: " << runs.size() << " (" << failed << " failed), iterations: " << iterations.size()
     << ", points per iteration: " << spec.points_per_iteration << "\n"
     << "- strategy: "
     << (spec.strategy == SamplingStrategy::srsm              ? "SRSM domain reduction"
         : spec.strategy == SamplingStrategy::adaptive_infill ? "adaptive infill"
                                                              : "batch expected improvement")
     << ", surrogate: RBF " << spec.basis << " ("
     << (spec.responses == ResponseMode::curve_points ? "one output per curve point" : "principal-component scores")
     << "), seed " << spec.seed << "\n";
  if (spec.cheap_level) md << cheap_level_line(spec, result);
  if (!best) {
    md << "\nNo successful run yet.\n";
    return md.str();
  }
  md << "- best objective: " << format_number(best->objective) << " (run " << best->iteration << "/" << best->point
     << ", " << best->kind << ")\n"
     << selection_line(result) << "\n";
  // What the numbers may hide, and the objective in the curve's own units.
  const StudyDiagnostics diagnostics = study_diagnostics(spec, runs, iterations, best, result);
  if (!diagnostics.warnings.empty()) {
    md << "## Warnings\n\n";
    for (const auto& w : diagnostics.warnings) md << "- **warning:** " << w << "\n";
    md << "\n";
  }
  if (!diagnostics.misfits.empty()) {
    md << "## Misfit of the best run\n\n| target | RMS misfit | unit | noise of the data (2nd differences) | misfit / "
          "noise |\n"
          "|---|---|---|---|---|\n";
    for (const auto& m : diagnostics.misfits)
      md << "| " << m.target << " | " << format_number(m.rms) << " | " << m.y_label << " | " << format_number(m.noise)
         << " | " << (m.noise > 0.0 ? format_number(m.rms / m.noise) : std::string("-")) << " |\n";
    md << "\n";
  }
  variables_section(md, spec, *best, result ? result->value("uncertainty", nlohmann::json()) : nlohmann::json());
  targets_section(md, spec, *best);
  if (!images.empty()) {
    md << "\n## Plots\n\n";
    for (const auto& image : images) md << "![" << image << "](" << image << ")\n\n";
  }
  failures_and_files_section(md, runs, failed);
  return md.str();
}

}  // namespace demfit::identify::detail
