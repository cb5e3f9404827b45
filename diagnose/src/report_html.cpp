// report.html of a diagnosis (see report_html.hpp).
#include "report_html.hpp"

#include "demfit/identify/report_html.hpp"
#include "demfit/identify/safe_output.hpp"
#include "text_format.hpp"

namespace demfit::diagnose::detail {

void write_diagnosis_html(const Diagnosis& d, const std::string& markdown, const std::filesystem::path& out) {
  identify::HtmlReport html("demfit diagnose", out);
  html.heading(2, std::string("Verdict: ") + verdict_text(d.verdict) +
                      (d.chosen >= 0 ? " (" + d.refits[static_cast<std::size_t>(d.chosen)].effect + ")" : ""));
  html.paragraph(d.summary);
  html.heading(2, "Candidates");
  std::vector<std::vector<std::string>> rows = {
      {"base", std::to_string(d.base_variables.size()), format("%.5g", d.base_criterion_chi_square),
       format("%.5g", d.base_bic), "0", "-"}};
  for (std::size_t i = 0; i < d.refits.size(); ++i) {
    const CandidateFit& r = d.refits[i];
    rows.push_back({"base + " + r.effect, std::to_string(r.fit.values.size()), format("%.5g", r.criterion_chi_square),
                    format("%.5g", r.bic), format("%.4g", r.delta_bic),
                    static_cast<int>(i) == d.chosen ? "yes" : "no"});
  }
  html.table({"model", "parameters", "criterion chi-square", "BIC", "delta BIC", "named"}, rows);
  html.paragraph("An effect is named when its delta BIC exceeds " + format("%.3g", d.bic_threshold) +
                 " and its residual passes the noise tests.");
  html.heading(2, "Plots");
  for (const auto& target : d.targets)
    html.picture(identify::safe_slug("diagnosis_" + target.name) + ".png",
                 target.name + ": target, base fit, augmented fit; residuals with +-2 sigma");
  html.heading(2, "Full report");
  html.markdown(markdown, false);
  identify::write_html_report(out, "report.html", html);
}

}  // namespace demfit::diagnose::detail
