// Diagnosis report: markdown, JSON and a gnuplot PNG; see report.hpp.
#include "demfit/diagnose/report.hpp"
#include "demfit/diagnose/target_levels.hpp"
#include "report_html.hpp"
#include "text_format.hpp"
#include "demfit/identify/gnuplot.hpp"
#include "demfit/identify/safe_output.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

namespace demfit::diagnose {
namespace {

using detail::format;
using detail::scatter_use;

nlohmann::json analysis_json(const ResidualAnalysis& a) {
  nlohmann::json regions = nlohmann::json::array();
  for (const auto& r : a.regions)
    regions.push_back({{"region", r.label},
                       {"rms", r.rms},
                       {"max_abs", r.max_abs},
                       {"rms_over_sigma", r.rms_over_sigma},
                       {"max_over_sigma", r.max_over_sigma},
                       {"x_at_max", r.x_at_max}});
  return {{"points", a.points},
          {"fitted_parameters", a.fitted_parameters},
          {"sigma", a.sigma},
          {"rms", a.rms},
          {"max_abs", a.max_abs},
          {"rms_over_sigma", a.rms_over_sigma},
          {"max_over_sigma", a.max_over_sigma},
          {"structural", a.structural},
          {"alpha", a.alpha},
          {"runs_test",
           {{"runs", a.runs.runs},
            {"positive", a.runs.positive},
            {"negative", a.runs.negative},
            {"z", a.runs.z},
            {"p_value", a.runs.p_value}}},
          {"autocorrelation",
           {{"lag1", a.autocorrelation.lag1},
            {"durbin_watson", a.autocorrelation.durbin_watson},
            {"p_value", a.autocorrelation.p_value}}},
          {"variance",
           {{"ratio", a.variance.ratio},
            {"dof_residual", a.variance.dof_residual},
            {"dof_noise", a.variance.dof_noise},
            {"p_value", a.variance.p_value}}},
          {"smooth_structure",
           {{"statistic", a.smooth.statistic}, {"basis", a.smooth.basis}, {"p_value", a.smooth.p_value}}},
          {"regions", regions},
          {"worst_region", a.worst_region >= 0 ? nlohmann::json(a.regions[a.worst_region].label) : nlohmann::json()}};
}

std::string tests_row(const std::string& label, const ResidualAnalysis& a) {
  return format("| %s | %.3g | %.3g | %.3g | %d | %.3g | %.3f | %.3g | %.3g | %.3g | %.4g (%d) | %.3g | %s |\n",
                label.c_str(), a.alpha, a.rms_over_sigma, a.max_over_sigma, a.runs.runs, a.runs.p_value,
                a.autocorrelation.lag1, a.autocorrelation.p_value, a.variance.ratio, a.variance.p_value,
                a.smooth.statistic, a.smooth.basis, a.smooth.p_value, a.structural ? "structure" : "noise");
}

const CandidateFit* augmented(const Diagnosis& d) {
  if (d.chosen >= 0) return &d.refits[d.chosen];
  const CandidateFit* best = nullptr;
  for (const auto& r : d.refits)
    if (!best || r.delta_bic > best->delta_bic) best = &r;
  return best;
}

// One PNG per target: data, base and augmented fits (top), residuals (bottom). Every file goes
// through the atomic writer under a slug of the target name; gnuplot runs inside `out` from an
// argument vector and sees relative names only.
std::string plot_target(const Diagnosis& d, std::size_t t, Eigen::Index offset, const std::filesystem::path& out) {
  using identify::gnuplot_quote;
  const FitTarget& target = d.targets[t];
  const CandidateFit* aug = augmented(d);
  const std::string stem = identify::safe_slug("diagnosis_" + target.name);
  const std::string data = stem + ".dat", png = stem + ".png";
  std::ostringstream f;
  f << "# x data base_fit augmented_fit base_residual augmented_residual\n";
  f.precision(10);
  // In y units: whitened residuals (model scatter in the noise model) are mapped back, not scaled.
  const auto n = static_cast<Eigen::Index>(target.data.x.size());
  const Eigen::VectorXd base = raw_residual(target, d.base.residual.segment(offset, n));
  const Eigen::VectorXd augmented_fit = aug ? raw_residual(target, aug->fit.residual.segment(offset, n)) : base;
  for (std::size_t i = 0; i < target.data.x.size(); ++i) {
    const double rb = base(static_cast<Eigen::Index>(i)), ra = augmented_fit(static_cast<Eigen::Index>(i));
    f << target.data.x[i] << ' ' << target.data.y[i] << ' ' << target.data.y[i] + rb << ' ' << target.data.y[i] + ra
      << ' ' << rb << ' ' << ra << '\n';
  }
  identify::write_file_atomically(identify::path_inside(out, data), f.str());
  const std::string aug_title = aug ? "base + " + aug->effect + (d.chosen >= 0 ? "" : " (not accepted)") : "";
  std::ostringstream gp;
  gp << "set multiplot layout 2,1\n"
     << "set title " << gnuplot_quote(target.name + ": " + verdict_text(d.verdict)) << "\n"
     << "set xlabel " << gnuplot_quote(target.data.x_label) << "\nset ylabel " << gnuplot_quote(target.data.y_label)
     << "\n"
     << "plot " << gnuplot_quote(data) << " u 1:2 w p pt 7 ps 0.5 t 'target', '' u 1:3 w l lw 2 t 'base fit'"
     << (aug ? ", '' u 1:4 w l lw 2 t " + gnuplot_quote(aug_title) : std::string()) << "\n"
     << "set title 'residual (fit - target)'\nset ylabel " << gnuplot_quote("residual, " + target.data.y_label) << "\n"
     << format("plot %s u 1:5 w lp pt 7 ps 0.4 t 'base', %.10g w l lt 0 t '+-2 sigma', %.10g w l lt 0 notitle",
               gnuplot_quote(data).c_str(), 2 * target.sigma, -2 * target.sigma)
     << (aug ? ", '' u 1:6 w lp pt 7 ps 0.4 t " + gnuplot_quote(aug_title) : std::string()) << "\n"
     << "unset multiplot";
  const std::string problem = identify::gnuplot_png(out / png, gp.str(), 800);
  return problem.empty() ? std::string() : "warning: " + problem + "\n";
}

// The base fit's mean residual per target (target_levels.hpp), in the target's units and its noise.
std::string level_table(const Diagnosis& d) {
  Eigen::Index points = 0;
  for (const auto& t : d.targets) points += static_cast<Eigen::Index>(t.data.x.size());
  if (d.base.residual.size() != points) return "";
  std::string md =
      "\n## Level per target (mean of base fit - data: the part of the misfit a vertical shift of the curve would "
      "remove)\n\n| target | mean residual (y units) | mean/sigma | share of the squared residual |\n"
      "|---|---|---|---|\n";
  for (const auto& l : target_levels(d.targets, d.base.residual))
    md += format("| %s | %+.4g | %+.3g | %.0f %% |\n", l.target.c_str(), l.mean, l.mean_over_sigma,
                 100.0 * l.level_share);
  return md;
}

}  // namespace

nlohmann::json to_json(const Diagnosis& d) {
  nlohmann::json screening = nlohmann::json::array();
  for (const auto& s : d.screening)
    screening.push_back({{"effect", s.effect},
                         {"score", s.score},
                         {"p_value", s.p_value},
                         {"fraction_explained", s.fraction_explained},
                         {"absorbed_by_base", s.absorbed_by_base},
                         {"full_range_gain", s.full_range_gain},
                         {"evaluated", s.evaluated}});
  nlohmann::json refits = nlohmann::json::array();
  for (const auto& r : d.refits)
    refits.push_back({{"effect", r.effect},
                      {"parameters", r.fit.parameters},
                      {"chi_square", r.fit.chi_square},
                      {"criterion_chi_square", r.criterion_chi_square},
                      {"bic", r.bic},
                      {"aicc", r.aicc},
                      {"delta_bic", r.delta_bic},
                      {"delta_aicc", r.delta_aicc},
                      {"passes", r.passes},
                      {"evaluations", r.fit.evaluations},
                      {"residual", analysis_json(r.analysis)}});
  nlohmann::json targets = nlohmann::json::array();
  for (std::size_t i = 0; i < d.targets.size(); ++i) {
    const FitTarget& t = d.targets[i];
    nlohmann::json entry{
        {"name", t.name}, {"curve", t.curve}, {"sigma", t.sigma}, {"whitened", t.noise_factor.size() > 0}};
    if (i < d.scatter.size())
      entry["model_scatter"] = {
          {"sigma", d.scatter[i].sigma}, {"lag1", d.scatter[i].lag1}, {"runs", d.scatter[i].replicas}};
    targets.push_back(entry);
  }
  return {{"verdict", verdict_text(d.verdict)},
          {"effect", d.chosen >= 0 ? nlohmann::json(d.refits[d.chosen].effect) : nlohmann::json()},
          {"summary", d.summary},
          {"bic_threshold", d.bic_threshold},
          {"noise_given", d.noise_given},
          {"data_scatter_ratio", d.data_scatter_ratio},
          {"refit_search_evaluations", d.refit_search_evaluations},
          {"targets", targets},
          {"base",
           {{"parameters", d.base.parameters},
            {"chi_square", d.base.chi_square},
            {"criterion_chi_square", d.base_criterion_chi_square},
            {"refined_under_scatter", d.base_refined},
            {"search",
             {{"evaluations", d.base_search_evaluations},
              {"values", d.base_search_values},
              {"criterion_chi_square", d.base_search_criterion_chi_square}}},
            {"bic", d.base_bic},
            {"aicc", d.base_aicc},
            {"evaluations", d.base.evaluations},
            {"residual", analysis_json(d.base_analysis)},
            {"residual_against_data_noise", analysis_json(d.base_analysis_data_noise)}}},
          {"screening", screening},
          {"refits", refits},
          {"notes", d.notes},
          {"cost",
           {{"evaluations", d.evaluations},
            {"base_evaluations", d.base_evaluations},
            {"screening_evaluations", d.screening_evaluations},
            {"refit_evaluations", d.refit_evaluations},
            {"wall_seconds", d.wall_seconds}}}};
}

std::string markdown_report(const Diagnosis& d) {
  std::ostringstream md;
  md << "# demfit diagnose\n\n**Verdict: " << verdict_text(d.verdict) << "**"
     << (d.chosen >= 0 ? " — `" + d.refits[d.chosen].effect + "`" : std::string()) << "\n\n"
     << d.summary << "\n\n";
  md << "## Noise level\n\n| target | points | sigma (y units) | source | model scatter (y units, lag-1, runs) |\n"
        "|---|---|---|---|---|\n";
  for (std::size_t i = 0; i < d.targets.size(); ++i) {
    const FitTarget& t = d.targets[i];
    std::string scatter = "not measured";
    if (i < d.scatter.size()) {
      const bool whitened = t.noise_factor.size() > 0;
      scatter = format("%.4g, %.3f, %d (%s%s)", d.scatter[i].sigma, d.scatter[i].lag1, d.scatter[i].replicas,
                       scatter_use(whitened, d.data_scatter_ratio).c_str(), whitened ? "; sigma is the total" : "");
    }
    md << format("| %s | %zu | %.4g | %s | %s |\n", t.name.c_str(), t.data.x.size(), t.sigma,
                 d.noise_given ? "given (--noise)" : "estimated (Gasser-Sroka-Jennen-Steinmetz differences)",
                 scatter.c_str());
  }
  md << "\n## Residual tests (family-wise level alpha per row, each test at alpha/4; a candidate must pass "
        "at its level to be named; RMS and max of r/sigma with each target divided by its own noise level)\n\n"
        "| fit | alpha | RMS/sigma | max/sigma | runs | runs p | lag-1 | lag-1 p | variance ratio "
        "| variance p | smooth-structure stat (dof) | smooth p | verdict "
        "|\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  if (d.scatter_in_noise_model) md << tests_row("base, against the data noise alone", d.base_analysis_data_noise);
  md << tests_row("base", d.base_analysis);
  for (const auto& r : d.refits) md << tests_row("base + " + r.effect, r.analysis);
  md << level_table(d);
  md << "\n## Gap per region (RMS and max of the residual / the noise level of the region's target)\n\n"
        "| region | base RMS/sigma | base max/sigma";
  for (const auto& r : d.refits) md << " | +" << r.effect << " RMS/sigma | +" << r.effect << " max/sigma";
  md << " |\n|---|---|---";
  for (std::size_t i = 0; i < d.refits.size(); ++i) md << "|---|---";
  md << "|\n";
  for (std::size_t g = 0; g < d.base_analysis.regions.size(); ++g) {
    const auto& b = d.base_analysis.regions[g];
    md << format("| %s | %.3g | %.3g", b.label.c_str(), b.rms_over_sigma, b.max_over_sigma);
    for (const auto& r : d.refits)
      md << format(" | %.3g | %.3g", r.analysis.regions[g].rms_over_sigma, r.analysis.regions[g].max_over_sigma);
    md << " |\n";
  }
  md << "\n## Screening (score test at the base optimum)\n\nabsorbed by base: share of the effect's change of the "
        "curves that the base variables reproduce; gain at full range: chi-square the rest of it could bring at the "
        "far end of the effect's range (below the threshold: undetectable with these data).\n\n"
        "| effect | score | p | share of residual SS | absorbed by base | gain at full range |\n"
        "|---|---|---|---|---|---|\n";
  for (const auto& s : d.screening)
    md << format("| %s | %.4g | %.3g | %.3g | %.3g | %.4g |%s\n", s.effect.c_str(), s.score, s.p_value,
                 s.fraction_explained, s.absorbed_by_base, s.full_range_gain,
                 s.evaluated ? "" : " (a perturbed run failed)");
  md << "\n## Re-identification and criterion (threshold: delta BIC > " << format("%.3g", d.bic_threshold)
     << " and residual = noise)\n\n"
     << (d.criterion_replicas > 0
             ? format("criterion chi-square: mean over %d fresh runs of each optimum (the model scatters)\n\n",
                      d.criterion_replicas)
             : std::string())
     << "| model | parameters | chi-square | criterion chi-square | BIC | delta BIC | AICc | delta AICc | named |\n"
        "|---|---|---|---|---|---|---|---|---|\n";
  md << format("| base | %zu | %.5g | %.5g | %.5g | 0 | %.5g | 0 | - |\n", d.base_variables.size(), d.base.chi_square,
               d.base_criterion_chi_square, d.base_bic, d.base_aicc);
  for (std::size_t i = 0; i < d.refits.size(); ++i) {
    const auto& r = d.refits[i];
    md << format("| base + %s | %zu | %.5g | %.5g | %.5g | %.4g | %.5g | %.4g | %s |\n", r.effect.c_str(),
                 r.fit.values.size(), r.fit.chi_square, r.criterion_chi_square, r.bic, r.delta_bic, r.aicc,
                 r.delta_aicc, static_cast<int>(i) == d.chosen ? "**yes**" : "no");
  }
  md << "\n## Parameters\n\n| parameter | base";
  for (const auto& r : d.refits) md << " | base + " << r.effect;
  md << " |\n|---|---";
  for (std::size_t i = 0; i < d.refits.size(); ++i) md << "|---";
  md << "|\n";
  for (const auto& [name, value] : d.base.parameters) {
    md << format("| %s | %.6g", name.c_str(), value);
    for (const auto& r : d.refits) md << format(" | %.6g", r.fit.parameters.at(name));
    md << " |\n";
  }
  md << format("\n## Cost\n\n%d model evaluations (base fit %d, screening %d, re-fits %d), wall time %.1f s.\n",
               d.evaluations, d.base_evaluations, d.screening_evaluations, d.refit_evaluations, d.wall_seconds);
  if (!d.notes.empty()) {
    md << "\n## Notes\n\n";
    for (const auto& n : d.notes) md << "- " << n << "\n";
  }
  md << "\nPlots: diagnosis_<target>.png (target, base fit, augmented fit; residuals with +-2 sigma).\n";
  return md.str();
}

std::string write_diagnosis(const Diagnosis& d, const std::filesystem::path& out, bool plots) {
  // The one atomic writer: links are replaced, not followed; a full disk is an error.
  const std::string markdown = markdown_report(d);
  identify::write_file_atomically(out / "report.md", markdown);
  identify::write_file_atomically(out / "diagnosis.json", to_json(d).dump(2) + "\n");
  const bool draw = plots && identify::gnuplot_available();
  std::string warnings = plots && !draw ? "warning: gnuplot not found; plots skipped\n" : "";
  Eigen::Index offset = 0;
  for (std::size_t t = 0; draw && t < d.targets.size(); ++t) {
    warnings += plot_target(d, t, offset, out);
    offset += static_cast<Eigen::Index>(d.targets[t].data.x.size());
  }
  detail::write_diagnosis_html(d, markdown, out);  // after the plots: it embeds them
  return warnings;
}

}  // namespace demfit::diagnose
