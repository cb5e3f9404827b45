// The verdict in words; see verdict_summary.hpp.
#include "verdict_summary.hpp"

#include <algorithm>

#include "demfit/diagnose/target_levels.hpp"
#include "text_format.hpp"

namespace demfit::diagnose::detail {

std::string tests_text(const ResidualAnalysis& a) {
  return format(
      "runs p = %.3g, lag-1 autocorrelation %.3f (p = %.3g), variance ratio %.3g (p = %.3g), "
      "smooth structure p = %.3g",
      a.runs.p_value, a.autocorrelation.lag1, a.autocorrelation.p_value, a.variance.ratio, a.variance.p_value,
      a.smooth.p_value);
}

namespace {

// Screened candidates that could not pass the criterion even at the far end of their range (the
// part of their change the base variables cannot reproduce gains less chi-square than the
// threshold): silence about them is not evidence of absence, and the user should hear so.
std::string undetectable_text(const Diagnosis& d) {
  std::string names;
  for (const auto& s : d.screening)
    if (s.evaluated && s.full_range_gain < d.bic_threshold)
      names += (names.empty() ? "'" : ", '") + s.effect + "'" +
               format(" (gain %.3g, %.0f %% of its change absorbed)", s.full_range_gain, 100.0 * s.absorbed_by_base);
  if (names.empty()) return "";
  return " Undetectable with these data: " + names +
         format(
             " — even at the far end of its range (the screening step extrapolated linearly), the part of the change "
             "the base variables cannot reproduce gains "
             "less chi-square than the threshold %.3g, so these data can neither show nor exclude it; a curve or case "
             "where it acts differently from the base variables would.",
             d.bic_threshold);
}

// A candidate that wins the criterion and fails only the lag-1 test is not named (its residual is
// not noise), but a right model fails that test alone when the data are one realisation of the
// scatter too (fails_only_autocorrelation); the user should hear that it is the likely answer.
std::string lag1_only_text(const CandidateFit& c, double bic_threshold) {
  if (!(c.delta_bic > bic_threshold) || !fails_only_autocorrelation(c.analysis)) return "";
  return format(
             " It wins the criterion (delta BIC %.4g > %.3g) and fails only the lag-1 test (p = %.3g), which a right "
             "model can fail when the data are one realisation of a flow as chaotic as the model's (docs/diagnose.md): "
             "'",
             c.delta_bic, bic_threshold, c.analysis.autocorrelation.p_value) +
         c.effect + "' is the likely answer, not proven.";
}

// The verdict alone, without the note on undetectable candidates.
std::string summarise_verdict(const Diagnosis& d) {
  const ResidualAnalysis& a = d.base_analysis;
  std::string where;
  if (a.worst_region >= 0)
    where = "; largest misfit in " + a.regions[a.worst_region].label +
            format(" (RMS/sigma %.3g)", a.regions[a.worst_region].rms_over_sigma);
  // Each target normalised by its own noise level before pooling (targets may differ in units).
  const std::string base_numbers =
      format("base fit RMS/sigma %.3g, max/sigma %.3g", a.rms_over_sigma, a.max_over_sigma);
  switch (d.verdict) {
    case Verdict::no_missing_effect:
      if (d.scatter_in_noise_model)
        return "No missing effect beyond the model's own scatter: the base residual is structural against the data "
               "noise alone (" +
               tests_text(d.base_analysis_data_noise) +
               ") but consistent with data noise + the run-to-run scatter of the model (" + tests_text(a) + "); " +
               base_numbers + (d.refits.empty() ? "." : "; no candidate is favoured under that noise.") +
               " A finer model (less scatter) or more data is needed to detect a smaller effect.";
      return "No missing effect: the base residual is consistent with noise (" + tests_text(a) + "); " + base_numbers +
             ".";
    case Verdict::effect_identified: {
      const CandidateFit& c = d.refits[d.chosen];
      return "Missing effect: '" + c.effect + "'" +
             format(" (delta BIC %.4g > %.3g, delta AICc %.4g). ", c.delta_bic, d.bic_threshold, c.delta_aicc) +
             "Residual before: " + tests_text(a) + where + ". After: " + tests_text(c.analysis) +
             format(". RMS/sigma %.3g -> %.3g, max/sigma %.3g -> %.3g (each target by its own noise level).",
                    a.rms_over_sigma, c.analysis.rms_over_sigma, a.max_over_sigma, c.analysis.max_over_sigma);
    }
    case Verdict::ambiguous: {
      std::string names;
      for (int i : d.tied)
        names += (names.empty() ? "'" : ", '") + d.refits[i].effect + "'" +
                 format(" (delta BIC %.4g)", d.refits[i].delta_bic);
      return "Ambiguous: the base residual is not noise (" + tests_text(a) + where + "); " + base_numbers +
             ". Each of " + names +
             format(
                 " is favoured over the base by more than %.3g in BIC, and their BICs are within %.3g of each "
                 "other",
                 d.bic_threshold, d.bic_threshold) +
             ": these data cannot tell them apart; no effect is named (add a curve or case that separates them).";
    }
    case Verdict::unexplained_structural: {
      std::string best;
      if (!d.refits.empty()) {
        const auto it = std::max_element(d.refits.begin(), d.refits.end(),
                                         [](const auto& x, const auto& y) { return x.delta_bic < y.delta_bic; });
        best = " Best candidate '" + it->effect + "'" +
               format(": delta BIC %.4g, RMS/sigma after %.3g", it->delta_bic, it->analysis.rms_over_sigma) +
               (it->analysis.structural ? ", residual still structural (" + tests_text(it->analysis) + ")"
                                        : std::string(", below the criterion")) +
               "." + lag1_only_text(*it, d.bic_threshold);
      } else {
        best = " No candidate effects were given.";
      }
      return "Unexplained structural residual: the base residual is not noise (" + tests_text(a) + where + "); " +
             base_numbers + "." + best + " No candidate explains it; no effect is named.";
    }
  }
  return "";
}

// Base variables the base fit left within 1 % of their range from a bound. A fit that runs to the
// end of the range the user allowed is asking for more than the base model gives there: a missing
// effect the variable stands in for (sliding friction pushed to its limit in place of cohesion),
// or a range too narrow. Said beside any verdict but a named effect (which then explains it),
// since the verdict only holds inside the range.
std::string bound_text(const Diagnosis& d) {
  std::string names;
  for (std::size_t j = 0; j < d.base_variables.size() && j < d.base.values.size(); ++j) {
    const FitVariable& v = d.base_variables[j];
    const double value = d.base.values[j];
    const int side = near_bound(v, value, 0.01);
    if (side == 0) continue;
    const bool high = side > 0;
    names += (names.empty() ? "'" : ", '") + v.name + "'" +
             format(" at %.4g (its %s bound %.4g)", value, high ? "upper" : "lower", high ? v.upper : v.lower);
  }
  if (names.empty()) return "";
  return " The base fit ran to the end of its range: " + names +
         ". The data ask for more than the base model gives inside its ranges (an effect that variable stands in "
         "for, or a range too narrow): this verdict holds only inside the ranges.";
}

// Opposite levels of the base fit between targets (target_levels.hpp); empty when the base residual
// is missing (a failed base fit) or the levels do not disagree.
std::string levels_text(const Diagnosis& d) {
  Eigen::Index points = 0;
  for (const auto& t : d.targets) points += static_cast<Eigen::Index>(t.data.x.size());
  if (d.targets.size() < 2 || d.base.residual.size() != points) return "";
  return opposite_levels_text(target_levels(d.targets, d.base.residual));
}

}  // namespace

std::string summarise(const Diagnosis& d) {
  const std::string verdict = summarise_verdict(d);
  return d.verdict == Verdict::effect_identified ? verdict
                                                 : verdict + bound_text(d) + levels_text(d) + undetectable_text(d);
}

}  // namespace demfit::diagnose::detail
