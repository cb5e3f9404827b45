// report.html of a study (see report_html_study.hpp).
#include "report_html_study.hpp"

#include "demfit/identify/report_html.hpp"
#include "demfit/identify/reported_interval.hpp"
#include "demfit/identify/study_answer.hpp"
#include "demfit/identify/study_warnings.hpp"
#include "report_plots.hpp"
#include "study_support.hpp"

namespace demfit::identify::detail {
namespace {

// The identified values and their reported intervals (the same as report.md and best_parameters.json).
void answer_section(HtmlReport& html, const StudySpec& spec, const StudyAnswer& answer,
                    const std::optional<nlohmann::json>& result) {
  const nlohmann::json uncertainty = result ? result->value("uncertainty", nlohmann::json()) : nlohmann::json();
  std::vector<std::vector<std::string>> rows;
  for (const auto& v : spec.variables) {
    const double value = answer.run->parameters.at(v.name);
    std::string interval = "-", identifiable = "-";
    if (uncertainty.is_object()) {
      const ReportedInterval reported = reported_interval(uncertainty, v.name, value);
      interval = interval_text(reported);
      identifiable = reported.identifiable ? "yes" : "NO";
    }
    std::string bounds = "[";
    bounds.append(format_number(v.lower)).append(", ").append(format_number(v.upper)).append("]");
    if (v.log_scale) bounds.append(" log");
    rows.push_back({v.name, format_number(value), interval, bounds, identifiable});
  }
  html.table({"variable", "identified", "95 % interval", "bounds", "identifiable"}, rows);
}

bool starts_with(const std::string& text, const char* prefix) { return text.rfind(prefix, 0) == 0; }

// The plots of `images` whose names start with `prefix`, in order.
void pictures_with_prefix(HtmlReport& html, const std::vector<std::string>& images, const char* prefix,
                          const std::string& caption) {
  for (const auto& image : images)
    if (starts_with(image, prefix)) html.picture(image, caption + " (" + image + ")");
}

}  // namespace

void write_study_html(const StudySpec& spec, const std::vector<EvaluationRecord>& runs,
                      const std::vector<IterationRecord>& iterations, const std::optional<nlohmann::json>& result,
                      const std::filesystem::path& store, const std::vector<std::string>& images,
                      const std::string& markdown, const std::filesystem::path& output_dir) {
  HtmlReport html("demfit identification report: " + spec.name, output_dir);
  const StudyAnswer answer = study_answer(runs, result, store.string());
  html.heading(2, "Answer");
  std::vector<std::string> facts = {"status: " + study_status(result)};
  if (answer.run)
    facts.push_back("answer: run " + std::to_string(answer.run->iteration) + "/" + std::to_string(answer.run->point) +
                    ", objective " + format_number(answer.run->objective) + ": " + answer.why);
  html.list(facts);
  if (!answer.run) {
    html.paragraph("No successful run yet.");
  } else {
    answer_section(html, spec, answer, result);
    for (const auto& w : study_diagnostics(spec, runs, iterations, answer.run, result).warnings) html.warning(w);
  }
  if (!images.empty()) {
    html.heading(2, "Fits: measured vs simulated");
    pictures_with_prefix(html, images, "target_", "target and the answer's simulated curve");
    html.heading(2, "Convergence");
    pictures_with_prefix(html, images, "objective_history", "objective per run and best per iteration");
    pictures_with_prefix(html, images, "variable_", "predicted optimum and subregion per iteration");
  }
  const nlohmann::json uncertainty = result ? result->value("uncertainty", nlohmann::json()) : nlohmann::json();
  const nlohmann::json posterior =
      uncertainty.is_object() ? uncertainty.value("posterior", nlohmann::json()) : nlohmann::json();
  if (posterior.is_object() && posterior.contains("pair_plot") && posterior["pair_plot"].is_string()) {
    html.heading(2, "Posterior");
    // Drawn by the study into its own folder, which is output_dir unless the report is rebuilt elsewhere.
    const std::string pairs = posterior["pair_plot"].get<std::string>();
    const auto folder = std::filesystem::exists(output_dir / pairs) ? output_dir : store.parent_path();
    html.picture(pairs, "posterior pairs: marginals and pairwise samples of the variables", folder);
  }
  html.heading(2, "Full report");
  html.markdown(markdown, false);
  write_html_report(output_dir, "report.html", html);
}

}  // namespace demfit::identify::detail
