// `demfit reproduce table1` (paper Table 1, docs/spec.md 2.1): K_bulk from E and nu, then NORMK and SHEARK
// identified from the shipped synthetic pressure-volume curve, starting from the LS-DYNA defaults.
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "demfit/cases/case_spec.hpp"
#include "demfit/cases/model_factory.hpp"
#include "demfit/cases/study_model.hpp"
#include "demfit/cases/reproduce.hpp"
#include "demfit/identify/study.hpp"
#include "demfit/identify/study_spec.hpp"
#include "builtin_cases.hpp"
#include "reproduce_study.hpp"
#include "number_text.hpp"

namespace demfit::cases {
namespace {

// Generating values of the shipped synthetic curve = the paper's identified values (Table 1).
constexpr double kPaperNormk = 0.875046;
constexpr double kPaperSheark = 0.299582;

std::string percent(double value, double truth) { return fmt("%+.2f", 100.0 * (value - truth) / truth) + " %"; }

// One "demfit" cell: the identified value and its 95 % interval as best_parameters.json, report.md
// and the LS-DYNA export give them (identify/reported_interval.hpp: the study's answer, the posterior
// interval, widened by interval-end runs where they say so), then the local least-squares centre
// (identify/uncertainty.hpp), which averages the noise of the runs near the optimum.
std::string identified_cell(const identify::StudyResult& r, const identify::VariableSpec& v, double truth) {
  const auto found = r.intervals.find(v.name);
  const identify::ReportedInterval interval = found != r.intervals.end() ? found->second : identify::ReportedInterval{};
  const double value = r.best.at(v.name);
  std::string cell = "**" + fmt("%.6f", value) + "** (" + percent(value, truth) + ")";
  if (interval.available) {
    cell += ", 95 % [" + fmt("%.6g", interval.lower) + ", " + fmt("%.6g", interval.upper) + "] (" + interval.method +
            "; truth " + (interval.lower <= truth && truth <= interval.upper ? "inside" : "OUTSIDE") + ")";
  }
  if (!interval.identifiable) cell += ", **not identifiable** (the interval spans most of its bounds)";
  const auto centre = r.least_squares_estimate.find(v.name);
  if (centre != r.least_squares_estimate.end() && std::isfinite(centre->second))
    cell += "; least-squares centre " + fmt("%.6f", centre->second) + " (" + percent(centre->second, truth) + ")";
  return cell;
}

}  // namespace

std::string reproduce_table1(const ReproduceOptions& o) {
  // The study is the shipped file (cases/table1_study[_quick].json): NORMK log-scaled from the
  // LS-DYNA default 0.01, the piston stroke capped at 4.5 mm (docs/reproduce.md says why).
  const identify::StudySpec spec =
      identify::load_study_file(o.cases_dir / (o.quick ? "table1_study_quick.json" : "table1_study.json"));
  const auto model = make_model(spec.model_reference, spec.model_overrides, spec.base_dir);
  const auto cheap_model = make_cheap_level_model(spec, o.out_dir / "table1");  // a study with a cheap level
  identify::RunOptions run = detail::study_run_options(o, o.out_dir / "table1");
  run.cheap_model = cheap_model.get();
  const identify::StudyResult r = identify::run_study(spec, *model, run);

  const CaseSpec pellet = parse_case(nlohmann::json::parse(detail::kBuiltinPelletCompression));
  const double bulk = pellet.material.bulk_modulus();
  std::string t = "Table 1: material properties of pellets and identified numerical parameters\n\n";
  t += "| Parameter | paper | demfit |\n|---|---|---|\n";
  t += "| Young's modulus, E (MPa) | 1,060 | " + fmt("%.0f", pellet.material.youngs_modulus / 1e6) + " (input) |\n";
  t += "| Poisson's ratio, nu | 0.4 | " + fmt("%.2f", pellet.material.poisson_ratio) + " (input) |\n";
  t += "| K_bulk = E / (3(1 - 2 nu)) (MPa) | 1,767 | " + fmt("%.1f", bulk / 1e6) + " |\n";
  t += "| RADIUS (mm) | 1.86 | " + fmt("%.2f", pellet.material.radius * 1e3) + " |\n";
  t += "| NORMK (default = 0.01) | 0.875046 | " + identified_cell(r, spec.variables[0], kPaperNormk) + " |\n";
  t += "| SHEARK (default = 2/7 = 0.2857) | 0.299582 | " + identified_cell(r, spec.variables[1], kPaperSheark) +
       " |\n\n";
  t += "Identified from data/pellet_pressure_volume_synthetic.csv (SYNTHETIC: simulated by demfit at the\n"
       "paper's NORMK and SHEARK plus 1 % Gaussian noise, seed 2026; the experimental curve of Fig. 2 is not\n"
       "published). Start: LS-DYNA defaults NORMK = 0.01, SHEARK = 2/7. Bold: the study's answer, as in\n"
       "best_parameters.json (final_selection predicted_optimum: the run at the surrogate's final predicted\n"
       "optimum; without it the best run); 95 %: its reported interval (posterior on the runs near the\n" +
       std::string(spec.interval_check.max_steps > 0
                       ? "optimum, checked by runs at its ends; docs/study_format.md \"Interval-end checks\")"
                       : "optimum, NOT checked by runs at its ends: this study has no interval_check)") +
       "; percentages are\nthe error against the generating values.\n";
  t += "Runs used: " + std::to_string(r.runs - r.interval_check_runs) + " to the answer, " +
       std::to_string(r.interval_check_runs) + " more to check the intervals (" + std::to_string(r.failed_runs) +
       " failed), " + std::to_string(r.iterations) + " iterations, stopped: " + r.stop_reason + "; the answer's objective " + fmt("%.3g", r.best_objective) + ", wall time of this run " +
       fmt("%.0f", r.wall_seconds) + " s with " + std::to_string(o.jobs) + " parallel runs.\n";
  return t;
}

}  // namespace demfit::cases
