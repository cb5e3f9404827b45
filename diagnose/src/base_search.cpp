// The base model's criterion chi-square from a surrogate search over the base variables, so that
// base and re-fits are judged at optima found the same way; see fit_context.hpp and
// docs/diagnose.md, step 4.
#include <string>

#include "demfit/diagnose/surrogate_start.hpp"
#include "fit_context.hpp"
#include "text_format.hpp"

namespace demfit::diagnose::detail {

void search_base_optimum(const FitContext& c, Diagnosis& d) {
  const int runs = c.options.refit_search_evaluations;
  progress(c.options, c.started, "surrogate search over the base variables (" + std::to_string(runs) + " runs)");
  SurrogateStart s;
  try {
    s = surrogate_search_start(c.model, c.fixed, d.base_variables, d.targets, c.options.fit, runs,
                               c.options.fit.seed, {d.base.values}, {d.base.chi_square});
  } catch (const std::exception& e) {
    d.notes.push_back(std::string("the surrogate search over the base variables failed (") + e.what() +
                      "); the base criterion is its local fit's");
    return;
  }
  d.base_evaluations += s.evaluations;
  d.base_search_evaluations = s.evaluations;
  std::string at;
  identify::ParameterSet point = c.fixed;
  for (std::size_t j = 0; j < d.base_variables.size(); ++j) {
    point[d.base_variables[j].name] = s.values[j];
    at += (j ? ", " : "") + d.base_variables[j].name + " " + format("%.6g", s.values[j]);
  }
  if (s.values == d.base.values) {
    d.notes.push_back("a surrogate search over the base variables (" + std::to_string(s.evaluations) +
                      " runs) predicts its lowest chi-square at the base fit's own point");
    return;
  }
  const double replicated = replicated_chi_square(c, point, d.base_variables, d.targets, d.criterion_replicas,
                                                  s.run_chi_square, d.base_evaluations);
  d.base_search_values = s.values;
  d.base_search_criterion_chi_square = replicated;
  const bool lower = replicated < d.base_criterion_chi_square;
  d.notes.push_back(format("a surrogate search over the base variables (%d runs) predicts chi-square %.4g at ",
                           s.evaluations, s.predicted_chi_square) +
                    at + format("; the mean of %d fresh runs there is %.4g against %.4g at the base fit's optimum: ",
                                d.criterion_replicas, replicated, d.base_criterion_chi_square) +
                    (lower ? "the base criterion is the searched point's" : "the base fit's optimum is kept"));
  if (lower) d.base_criterion_chi_square = replicated;
}

}  // namespace demfit::diagnose::detail
