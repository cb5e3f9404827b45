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
      // The piston stroke is capped at 8 mm: the target needs ~2.5 mm, and soft candidates
      // (NORMK near 0.01) would otherwise run the full 30 mm (cost ~ stroke).
      {"model", {{"case", "pellet_compression"}, {"overrides", {{"pellet", {{"max_travel", 0.008}}}}}}},
      {"variables", json::array({
          {{"name", "normk"}, {"lower", 0.01}, {"upper", 5.0}, {"initial", 0.01}, {"log_scale", true}},
          {{"name", "sheark"}, {"lower", 0.1}, {"upper", 0.6}, {"initial", 2.0 / 7.0}}})},
      {"targets", json::array({{{"name", "pressure_volume"}, {"curve", "pressure_volume"},
                                {"csv", data_csv.string()}, {"x_column", "volume_cm3"},
                                {"y_column", "pressure_MPa"}, {"metric", "mse"}}})},
      {"sampling", {{"points_per_iteration", 6}}},
      // 6 points per iteration: 9 iterations + the verification run stay within 60 runs.
      {"stopping", {{"max_iterations", quick ? 3 : 9}}},
      {"seed", 1}};
}

std::string identified_cell(const identify::StudyResult& r, const std::string& name, double truth) {
  const double value = r.best.at(name);
  const auto ci = r.ci_half_width.find(name);
  std::string cell = fmt("%.6f", value);
  if (ci != r.ci_half_width.end() && std::isfinite(ci->second)) cell += " ± " + fmt("%.3g", ci->second);
  cell += " (" + fmt("%+.2f", 100.0 * (value - truth) / truth) + " %";
  for (const std::string& u : r.unidentifiable) {
    if (u == name) cell += ", not identifiable from this curve";
  }
  return cell + ")";
}

}  // namespace

std::string reproduce_table1(const ReproduceOptions& o) {
  const std::filesystem::path data_csv = std::filesystem::absolute(o.data_dir / "pellet_pressure_volume_synthetic.csv");
  if (!std::filesystem::exists(data_csv)) {
    throw std::runtime_error("synthetic curve '" + data_csv.string() + "' is missing: run from the source tree or pass --data");
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
  t += "| NORMK (default = 0.01) | 0.875046 | " + identified_cell(r, "normk", kPaperNormk) + " |\n";
  t += "| SHEARK (default = 2/7 = 0.2857) | 0.299582 | " + identified_cell(r, "sheark", kPaperSheark) + " |\n\n";
  t += "Identified from data/pellet_pressure_volume_synthetic.csv (SYNTHETIC: simulated by demfit at the\n"
       "paper's NORMK and SHEARK plus 1 % Gaussian noise, seed 2026; the experimental curve of Fig. 2 is not\n"
       "published). Start: LS-DYNA defaults NORMK = 0.01, SHEARK = 2/7. ± = 95 % confidence half-width;\n"
       "percentages are the error against the generating values.\n";
  t += "Runs used: " + std::to_string(r.runs) + " (" + std::to_string(r.failed_runs) + " failed), " +
       std::to_string(r.iterations) + " iterations, " + (r.converged ? "converged" : "iteration limit") +
       ", best objective " + fmt("%.3g", r.best_objective) + ", wall time " + fmt("%.0f", r.wall_seconds) +
       " s with " + std::to_string(o.jobs) + " parallel runs.\n";
  return t;
}

}  // namespace demfit::cases
