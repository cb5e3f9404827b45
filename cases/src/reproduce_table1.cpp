// `demfit reproduce table1` (paper Table 1, SPEC 2.1): K_bulk from E and nu, then NORMK and SHEARK
// identified from the shipped synthetic pressure-volume curve, starting from the LS-DYNA defaults.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "demfit/cases/case_spec.hpp"
#include "demfit/cases/model_factory.hpp"
#include "demfit/cases/reproduce.hpp"
#include "demfit/identify/study.hpp"
#include "demfit/identify/study_spec.hpp"
#include "builtin_cases.hpp"

namespace demfit::cases {
namespace {

// Generating values of the shipped synthetic curve = the paper's identified values (Table 1).
constexpr double kPaperNormk = 0.875046;
constexpr double kPaperSheark = 0.299582;

std::string fmt(const char* pattern, double value) {
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, pattern, value);
  return buffer;
}

nlohmann::json table1_study(const std::filesystem::path& data_csv, bool quick) {
  using nlohmann::json;
  return json{
      {"demfit_study_version", 1},
      {"name", "table1_pellet"},
      // The piston stroke is capped at 4.5 mm: the target needs ~2 mm (67.16 -> 65.22 cm^3 over
      // a 10.18 cm^2 piston), and soft candidates (NORMK near 0.01) would otherwise run the full
      // 30 mm (cost ~ stroke); a capped curve is held flat beyond its end (docs/study_format.md).
      {"model", {{"case", "pellet_compression"}, {"overrides", {{"pellet", {{"max_travel", 0.0045}}}}}}},
      // NORMK log-scaled from the default 0.01 up to 2 (twice the paper's value; stiffer
      // candidates cost more: time step ~ 1/sqrt(NORMK)).
      {"variables",
       json::array({{{"name", "normk"}, {"lower", 0.01}, {"upper", 2.0}, {"initial", 0.01}, {"log_scale", true}},
                    {{"name", "sheark"}, {"lower", 0.1}, {"upper", 0.6}, {"initial", 2.0 / 7.0}}})},
      {"targets", json::array({{{"name", "pressure_volume"},
                                {"curve", "pressure_volume"},
                                {"csv", data_csv.string()},
                                {"x_column", "volume_cm3"},
                                {"y_column", "pressure_MPa"},
                                {"metric", "mse"}}})},
      {"sampling", {{"points_per_iteration", 6}}},
      // 6 points per iteration: 9 iterations + the verification run = 55 runs <= 60. The
      // tolerances are tight on purpose: run-to-run trajectory noise makes a 1 % stopping rule
      // fire while the optimum is still several % off (measured: stopped at 25 runs, -3.5 %).
      {"stopping", {{"max_iterations", quick ? 3 : 9}, {"design_tolerance", 0.001}, {"objective_tolerance", 0.001}}},
      {"seed", 1}};
}

std::string percent(double value, double truth) { return fmt("%+.2f", 100.0 * (value - truth) / truth) + " %"; }

// One "demfit" cell. The identified value is the centre of the local least-squares fit over the
// runs near the optimum (identify/uncertainty.hpp): with run-to-run trajectory noise comparable
// to the 1 % data noise, the single best run is partly the luckiest one, while the regression
// averages the noise of all nearby runs. The best run is shown beside it.
std::string identified_cell(const identify::StudyResult& r, const identify::VariableSpec& v, double truth) {
  const double best = r.best.at(v.name);
  bool flagged = false;
  for (const std::string& u : r.unidentifiable) flagged = flagged || u == v.name;
  const auto ci = r.ci_half_width.find(v.name);
  const double half = ci == r.ci_half_width.end() ? std::nan("") : ci->second;
  const auto centre = r.least_squares_estimate.find(v.name);
  const std::string best_text = "best run " + fmt("%.6f", best) + " (" + percent(best, truth) + ")";
  if (flagged && !std::isfinite(half)) {
    return "**not identifiable** near the optimum: over the last runs' spread its effect on the curve is below "
           "the run-to-run noise, so the local fit bounds no 95 % interval within [" +
           fmt("%g", v.lower) + ", " + fmt("%g", v.upper) + "]; " + best_text;
  }
  // A flagged variable's local fit is not trusted for a centre either: the best run stands.
  const double value =
      centre != r.least_squares_estimate.end() && std::isfinite(centre->second) && !flagged ? centre->second : best;
  std::string cell = "**" + fmt("%.6f", value) + "**";
  if (std::isfinite(half)) cell += " ± " + fmt("%.3g", half);
  cell += " (" + percent(value, truth);
  if (std::isfinite(half))
    cell += std::abs(value - truth) <= half ? ", truth inside the interval" : ", truth OUTSIDE the interval";
  if (flagged) cell += ", not identifiable";
  cell += "); " + best_text;
  return cell;
}

}  // namespace

std::string reproduce_table1(const ReproduceOptions& o) {
  const std::filesystem::path data_csv = std::filesystem::absolute(o.data_dir / "pellet_pressure_volume_synthetic.csv");
  if (!std::filesystem::exists(data_csv)) {
    throw std::runtime_error("synthetic curve '" + data_csv.string() +
                             "' is missing: run from the source tree or pass --data");
  }
  const nlohmann::json study = table1_study(data_csv, o.quick);
  const identify::StudySpec spec = identify::parse_study(study, o.out_dir);
  const auto model = make_model(spec.model_reference, spec.model_overrides, spec.base_dir);
  identify::RunOptions run;
  run.jobs = o.jobs;
  run.threads_per_job = o.threads_per_job;
  run.resume = o.resume;
  run.output_dir = o.out_dir / "table1";
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
       "published). Start: LS-DYNA defaults NORMK = 0.01, SHEARK = 2/7. Bold: centre of the local least-squares\n"
       "fit of the runs near the optimum; ± = its 95 % confidence half-width (regression Jacobian, data and\n"
       "simulation noise; docs/study_format.md); percentages are the error against the generating values.\n";
  t += "Runs used: " + std::to_string(r.runs) + " (" + std::to_string(r.failed_runs) + " failed), " +
       std::to_string(r.iterations) + " iterations, " + (r.converged ? "converged" : "iteration limit") +
       ", best objective " + fmt("%.3g", r.best_objective) + ", wall time in this session " +
       fmt("%.0f", r.wall_seconds) + " s with " + std::to_string(o.jobs) + " parallel runs.\n";
  return t;
}

}  // namespace demfit::cases
