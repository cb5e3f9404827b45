// Result files rebuilt from the study store alone (see report.hpp for the list).
#include "demfit/identify/report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "demfit/identify/curve_io.hpp"
#include "demfit/identify/gnuplot.hpp"
#include "demfit/identify/reported_interval.hpp"
#include "demfit/identify/safe_output.hpp"
#include "demfit/identify/study_answer.hpp"
#include "demfit/identify/study_spec.hpp"
#include "demfit/rbf_surrogate/bounds.hpp"
#include "report_html_study.hpp"
#include "report_plots.hpp"
#include "study_support.hpp"

namespace demfit::identify {
namespace {

std::string csv_number(double value) {
  if (!std::isfinite(value)) return "";
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.10g", value);
  return buffer;
}

std::string csv_text(const std::string& text) {
  std::string out = "\"";
  for (char c : text) out += (c == '"') ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string evaluations_csv(const StudySpec& spec, const std::vector<EvaluationRecord>& runs) {
  std::ostringstream out;
  out << "iteration,point,kind,status,objective,wall_s";
  for (const auto& v : spec.variables) out << "," << v.name;
  out << ",error\n";
  for (const auto& r : runs) {
    out << r.iteration << "," << r.point << "," << r.kind << "," << (r.ok ? "ok" : "failed") << ","
        << csv_number(r.objective) << "," << csv_number(r.wall_seconds);
    for (const auto& v : spec.variables)
      out << "," << csv_number(r.parameters.count(v.name) ? r.parameters.at(v.name) : NAN);
    out << "," << csv_text(r.error) << "\n";
  }
  return out.str();
}

std::string iterations_csv(const StudySpec& spec, const std::vector<IterationRecord>& iterations) {
  const auto variables = detail::rbf_variables(spec);
  std::ostringstream out;
  out << "iteration,runs_done,best_objective,predicted_objective,design_change,objective_change";
  for (const auto& v : spec.variables) out << "," << v.name << "_optimum," << v.name << "_lower," << v.name << "_upper";
  out << "\n";
  for (const auto& it : iterations) {
    out << it.iteration << "," << it.runs_done << "," << csv_number(it.best_objective) << ","
        << csv_number(it.predicted_objective) << "," << csv_number(it.design_change) << ","
        << csv_number(it.objective_change);
    const auto band = detail::region_band(variables, it);
    for (std::size_t j = 0; j < spec.variables.size(); ++j)
      out << "," << csv_number(it.predicted_parameters.at(spec.variables[j].name)) << "," << csv_number(band.first[j])
          << "," << csv_number(band.second[j]);
    out << "\n";
  }
  return out.str();
}

nlohmann::json best_parameters_json(const StudySpec& spec, const EvaluationRecord& best,
                                    const std::optional<nlohmann::json>& result) {
  const nlohmann::json uncertainty = result ? result->value("uncertainty", nlohmann::json()) : nlohmann::json();
  nlohmann::json json = {{"study", spec.name},
                         {"model", spec.model_reference},
                         {"objective", best.objective},
                         {"run", {{"iteration", best.iteration}, {"point", best.point}}},
                         {"finished", result.has_value()},
                         {"converged", result ? result->value("converged", false) : false},
                         {"parameters", best.parameters}};
  for (const auto& e : spec.experiments)
    json["experiments"][e.name] = {{"case", e.model_reference}, {"overrides", e.model_overrides}};
  json["variables"] = nlohmann::json::object();
  for (const auto& v : spec.variables) {
    nlohmann::json entry = {{"value", best.parameters.at(v.name)},
                            {"initial", v.initial},
                            {"lower", v.lower},
                            {"upper", v.upper},
                            {"log_scale", v.log_scale}};
    if (uncertainty.is_object()) {
      // The reported interval (the same object as in report.md and the export), then the
      // linearised estimate for comparison.
      const ReportedInterval interval = reported_interval(uncertainty, v.name, best.parameters.at(v.name));
      if (interval.available) {
        entry["interval_95"] = {interval.lower, interval.upper};
        entry["interval_method"] = interval.method;
      }
      entry["identifiable"] = interval.identifiable;
      entry["linearised_ci95_half_width"] = uncertainty["ci_half_width"].value(v.name, nlohmann::json());
      entry["linearised_standard_error"] = uncertainty["standard_error"].value(v.name, nlohmann::json());
    }
    json["variables"][v.name] = entry;
  }
  if (uncertainty.is_object()) {
    json["correlation"] = {{"variables", uncertainty["variables"]}, {"matrix", uncertainty["correlation"]}};
    json["residual_variance"] = uncertainty["residual_variance"];
    json["degrees_of_freedom"] = uncertainty["degrees_of_freedom"];
  }
  return json;
}

}  // namespace

ReportSummary write_report(const StudyStore& store, const std::filesystem::path& output_dir, bool plots) {
  const StudySpec spec = parse_study(store.study_json(), output_dir);
  const auto runs = store.evaluations();
  const auto iterations = store.iterations();
  const auto result = store.result();
  const EvaluationRecord* best = study_answer(runs, result, store.path().string()).run;
  ReportSummary summary;
  std::filesystem::create_directories(output_dir);
  write_file_atomically(output_dir / "evaluations.csv", evaluations_csv(spec, runs));
  write_file_atomically(output_dir / "iterations.csv", iterations_csv(spec, iterations));
  write_file_atomically(output_dir / "study_resolved.json", store.study_json().dump(2) + "\n");
  summary.files_written += 3;
  if (best) {
    write_file_atomically(output_dir / "best_parameters.json",
                          best_parameters_json(spec, *best, result).dump(2) + "\n");
    ++summary.files_written;
    for (const auto& target : spec.targets) {
      // File names from user strings go through the one slug function and stay in output_dir.
      write_curve_csv(path_inside(output_dir, safe_slug("target_" + target.name + ".csv")), target.data);
      const auto found = best->curves.find(target.curve);
      if (found != best->curves.end())
        write_curve_csv(path_inside(output_dir, safe_slug("best_" + target.name + ".csv")), found->second);
      summary.files_written += 2;
    }
  }
  std::vector<std::string> images;
  if (plots) {
    if (!gnuplot_available()) {
      summary.plot_warning = "gnuplot not found: plots skipped (apt-get install gnuplot-nox)";
    } else {
      const auto written = detail::write_plots(spec, runs, iterations, best, output_dir);
      images = written.first;
      summary.plot_warning = written.second;
      summary.plots_written = !images.empty();
      summary.files_written += static_cast<int>(images.size());
    }
  }
  const std::string markdown = detail::report_markdown(spec, runs, iterations, best, result, images);
  write_file_atomically(output_dir / "report.md", markdown);
  detail::write_study_html(spec, runs, iterations, result, store.path(), images, markdown, output_dir);
  summary.files_written += 2;
  return summary;
}

}  // namespace demfit::identify
