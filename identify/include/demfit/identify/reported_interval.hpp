#pragma once
// The identified value of a variable and its 95 % interval as every output shows it:
// report.md, best_parameters.json, the command line's summary, `reproduce granudrum` and the
// LS-DYNA export comments all read it through reported_interval() from the stored result, so
// they cannot disagree.
//
// The interval is the 95 % marginal of the posterior (Gibbs sampling on the local linear
// residual surrogate, noise level estimated from the runs; uncertainty.hpp), which stays right
// when another parameter is poorly pinned. Only when the posterior could not be computed (too
// few runs near the optimum) is it the linearised value ± half-width, conditional on the other
// parameters; `method` says which.
#include <limits>
#include <string>

#include <nlohmann/json.hpp>

namespace demfit::identify {

struct ReportedInterval {
  bool available = false;  // false: the study has no uncertainty (not finished, or too few runs)
  double value = std::numeric_limits<double>::quiet_NaN();  // the answer's value (model units)
  double lower = std::numeric_limits<double>::quiet_NaN();  // 95 % interval, model units
  double upper = std::numeric_limits<double>::quiet_NaN();
  bool identifiable = true;  // false: the data cannot pin the variable down
  // "posterior", "posterior, widened by interval-end runs" (interval_check.hpp), either with
  // ", widened to the answer" (the answer, the best run or a final selection's choice, lay outside the posterior's
  // 95 % interval and no interval check stepped outward from it, so the interval is stretched to it) or
  // "linearised"
  std::string method;
};

// `uncertainty` is the "uncertainty" object of a study result (null when absent); `value` the
// best run's value of the variable.
ReportedInterval reported_interval(const nlohmann::json& uncertainty, const std::string& variable, double value);

// One line for tables and comments: "[0.52, 0.61] (posterior)", or "-" when not available.
std::string interval_text(const ReportedInterval& interval);

}  // namespace demfit::identify
