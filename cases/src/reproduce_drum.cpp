// `demfit reproduce figures` (Figs. 4-5) and `demfit reproduce table3` (Table 3): the rotary
// drum studies of paper section 3 (docs/spec.md 2.2, 2.3).
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "builtin_cases.hpp"
#include "demfit/cases/bed_angles.hpp"
#include "demfit/cases/case_output.hpp"
#include "demfit/cases/case_runner.hpp"
#include "demfit/cases/case_spec.hpp"
#include "demfit/cases/model_factory.hpp"
#include "demfit/cases/study_model.hpp"
#include "demfit/cases/reproduce.hpp"
#include "demfit/cases/result_cache.hpp"
#include "demfit/identify/objective.hpp"
#include "demfit/identify/reported_interval.hpp"
#include "demfit/identify/roundoff_replicates.hpp"
#include "demfit/identify/run_program.hpp"
#include "demfit/identify/safe_output.hpp"
#include "demfit/identify/json_document.hpp"
#include "demfit/identify/study.hpp"
#include "demfit/identify/study_spec.hpp"
#include "reproduce_study.hpp"
#include "number_text.hpp"

namespace demfit::cases {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// The drum of a reproduction is the model of the shipped Table 3 study (cases/table3_study.json;
// the quick one is a cheaper drum of the same cross-section and fill fraction, docs/reproduce.md):
// Figs. 4-5 and the Table 3 target run it at other coarse-graining models and factors, so every
// run of one reproduction uses the same drum.
json table3_study_document(const ReproduceOptions& o) {
  return identify::read_json_file(o.cases_dir / (o.quick ? "table3_study_quick.json" : "table3_study.json"),
                                  "Table 3 study");
}

CaseSpec drum_spec(const json& study, CoarseGraining model, double s) {
  json document = json::parse(detail::kBuiltinRotaryDrum);
  json overrides = study.at("model").value("overrides", json::object());
  overrides["drum"]["coarse_graining"] = to_string(model);
  overrides["drum"]["scale_factor"] = s;
  document.merge_patch(overrides);
  return parse_case(document);
}

// Runs gnuplot on a script file in `dir`, from an argument vector (never a shell: --out may hold
// any text); a missing gnuplot is a warning in the text, not an error.
std::string run_gnuplot(const fs::path& dir, const std::string& script) {
  if (identify::run_program({"gnuplot", script}, dir) != 0)
    return "(gnuplot not available or failed: PNG not written; data in CSV)\n";
  return "";
}

void write_fig4_script(const fs::path& dir, const std::vector<std::string>& runs, double duration) {
  std::ostringstream gp;
  gp << "set terminal pngcairo size 1500,1000 noenhanced\nset output 'fig4_particles.png'\n"
     << "set multiplot layout 2,3 title 'Fig. 4: particles in the drum cross-section at t = " << duration << " s'\n"
     << "set size ratio -1\nset xrange [-52:52]\nset yrange [-52:52]\nset xlabel 'x [mm]'\nset ylabel 'y [mm]'\n"
     << "set object 1 circle at 0,0 size 50 fc rgb 'black' fs empty\nset datafile separator ','\n";
  for (const std::string& run : runs) {
    gp << "set title '" << run << "'\nplot '" << run << "/particles_end.csv' skip 2 using 1:2:4 with circles "
       << "fs transparent solid 0.5 lc rgb '#1f77b4' notitle\n";
  }
  gp << "unset multiplot\n";
  identify::write_file_atomically(dir / "fig4_particles.gp", gp.str());
}

void write_fig5_script(const fs::path& dir, const std::vector<std::string>& runs) {
  std::ostringstream gp;
  gp << "set terminal pngcairo size 1000,600 noenhanced\nset output 'fig5_torque.png'\nset datafile separator ','\n"
     << "set title 'Fig. 5: drive torque (z-moment) of the drum'\nset xlabel 'time [s]'\nset ylabel 'torque [N m]'\n"
     << "set key outside right\nplot ";
  for (std::size_t i = 0; i < runs.size(); ++i) {
    gp << (i ? ", " : "") << "'" << runs[i] << "/torque.csv' skip 4 using 1:2 with lines title '" << runs[i] << "'";
  }
  gp << "\n";
  identify::write_file_atomically(dir / "fig5_torque.gp", gp.str());
}

// The paper's optimal values (Table 3), shown beside demfit's: a published fact, not a study input.
std::string paper_value(const std::string& variable) {
  static const std::pair<const char*, double> kPaperOptimal[] = {
      {"ndamp", 0.558648808},      {"tdamp", 0.547304765},      {"frics", 0.437766112},
      {"fricr", 0.088137162},      {"normk", 0.095010325},      {"sheark", 0.004870718},
      {"wall_frics", 0.398444369}, {"wall_fricd", 0.186624382}, {"wall_damp", 0.101806949}};
  for (const auto& [name, value] : kPaperOptimal)
    if (variable == name) return fmt("%.9g", value);
  return "-";
}

double rms_surface_error(const identify::Curve& target, const identify::Curve& computed) {
  const std::vector<double> f = identify::resample_monotone(computed, target.x);
  double sum = 0.0;
  for (std::size_t i = 0; i < f.size(); ++i) sum += (f[i] - target.y[i]) * (f[i] - target.y[i]);
  return std::sqrt(sum / static_cast<double>(f.size()));
}

// The first replicate index of the report's re-runs: past those a study's final selection may use
// (study_spec.hpp), so the trajectories that chose the answer do not also judge it.
constexpr int kFirstReportReplicate = identify::kMaxReplicates;

// Surface errors of `count` runs at `values`: the run already made (`first_error`), then
// round-off replicates (roundoff_replicates.hpp), each another trajectory of the same physics. A
// replicate that fails is left out (the spread's count says so) rather than losing the finished
// study's table.
std::vector<double> replicate_errors(const identify::Model& model, const identify::StudySpec& spec,
                                     const identify::ParameterSet& values, double first_error,
                                     const identify::Curve& target, int count,
                                     const identify::EvaluationContext& context) {
  std::vector<double> errors{first_error};
  for (int r = 0; r + 1 < count; ++r) {
    try {
      const identify::CurveSet curves =
          model.evaluate(identify::replicate_parameters(spec, values, kFirstReportReplicate + r), context);
      errors.push_back(rms_surface_error(target, curves.at("free_surface")));
    } catch (const std::exception&) {}
  }
  return errors;
}

std::string spread_text(const identify::ReplicateSpread& s) {
  return fmt("%.2f", s.mean) + " ± " + fmt("%.2f", s.standard_deviation) + " mm (" + fmt("%.2f", s.lowest) + "–" +
         fmt("%.2f", s.highest) + ", " + std::to_string(s.count) + " runs)";
}

// How sure the single-run ratio is: both points re-run as round-off replicates (Table 3's s = 4
// surface of ~141 coarse particles moves by millimetres between trajectories: docs/reproduce.md).
std::string replicate_text(const identify::Model& model, const identify::StudySpec& spec,
                           const identify::ParameterSet& best, double error_before, double error_after,
                           const identify::Curve& target, int count, const identify::EvaluationContext& context) {
  identify::ParameterSet initial;
  for (const identify::VariableSpec& v : spec.variables) initial[v.name] = v.initial;
  const identify::ReplicateSpread before =
      identify::replicate_spread(replicate_errors(model, spec, initial, error_before, target, count, context));
  const identify::ReplicateSpread after =
      identify::replicate_spread(replicate_errors(model, spec, best, error_after, target, count, context));
  const identify::RatioOfMeans ratio = identify::ratio_of_means(after, before);
  return "How sure: each point run " + std::to_string(count) +
         " times (the run above, then round-off replicates: every variable moved by " +
         std::to_string(kFirstReportReplicate + 1) + "e-7 to " + std::to_string(kFirstReportReplicate + count - 1) +
         "e-7 of its range, other trajectories of the same physics; " + std::to_string(2 * (count - 1)) +
         " runs outside the study). Surface RMS error at the initial values " + spread_text(before) +
         ", at the identified values " + spread_text(after) + "; ratio of the means " + fmt("%.2f", ratio.ratio) +
         " (±2 standard errors " + fmt("%.2f", ratio.lower) + "–" + fmt("%.2f", ratio.upper) +
         "). The single-run ratio above compares one trajectory of each point.\n";
}

// How far the answer's spheres interpenetrate, from one more run at the answer (the drum summary's
// line, dem_core/overlap_statistics.hpp): a soft NORMK can make the coarse bed as dense as the fine
// one by overlap instead of by packing (docs/measurements/2026-12-06-table3-soft-normk-and-transfer.md), which the surface
// error alone does not show.
std::string overlap_text(const json& study, const identify::ParameterSet& best, const ReproduceOptions& o) {
  CaseRunOptions run;
  run.threads = o.threads_per_job;
  const CaseResult answer = run_case(drum_spec(study, CoarseGraining::scg, 4.0), best, run);
  for (const auto& [label, value] : answer.summary)
    if (label == kParticleOverlapLabel)
      return "Particle overlap at the identified values (one run, end time): mean / max " + value +
             " % of the smaller radius (a common DEM guideline keeps it near 1 %; far more means the bed's density "
             "comes from interpenetration).\n";
  return "";
}

std::string table3_cell(const identify::StudyResult& r, const std::string& name) {
  std::string cell = fmt("%.6g", r.best.at(name));
  const auto found = r.intervals.find(name);  // the interval of report.md and best_parameters.json
  if (found == r.intervals.end() || !found->second.available) return cell + " (no interval)";
  cell += ", 95 % " + identify::interval_text(found->second);
  if (!found->second.identifiable) cell += ", not identifiable";
  return cell;
}

}  // namespace

std::string reproduce_figures(const ReproduceOptions& o) {
  const fs::path dir = o.out_dir / "figures";
  fs::create_directories(dir);
  std::vector<std::string> runs;
  std::string text = "Figs. 4-5: rotary drum, s = 1, 2, 4, SCG and CVF (" +
                     std::string(o.quick ? "quick: 12.5 mm long drum, 1 s" : "3 s") +
                     " of rotation at 60 RPM); angle of repose: " + std::string(kClusterSurfaceAngleName) +
                     "\n\n| run | particles | radius [mm] | angle of repose [deg] | mean torque "
                     "[N m] | cached |\n|---|---|---|---|---|---|\n";
  double duration = 0.0;
  const json study = table3_study_document(o);
  for (CoarseGraining model : {CoarseGraining::scg, CoarseGraining::cvf}) {
    for (double s : {1.0, 2.0, 4.0}) {
      const CaseSpec spec = drum_spec(study, model, s);
      duration = spec.drum.duration;
      CaseRunOptions run;
      run.threads = std::max(1, o.jobs * o.threads_per_job);  // one run at a time: use all cores
      run.progress = o.progress;
      bool computed = false;
      const CaseResult result = cached_case_result(spec, run, &computed);
      std::string name = to_string(model);
      name += "_s";
      name += fmt("%g", s);
      runs.push_back(name);
      fs::create_directories(dir / name);
      write_case_result(dir / name, result, to_json(spec), {}, {});
      auto value = [&](const std::string& prefix) {
        for (const auto& [label, v] : result.summary)
          if (label.rfind(prefix, 0) == 0) return v;
        return std::string("?");
      };
      text += "| " + name + " | " + value("particles") + " | " + value("particle radius") + " | " +
              value("dynamic angle") + " | " + value("mean drive torque") + " | " + (computed ? "no" : "yes") + " |\n";
    }
  }
  write_fig4_script(dir, runs, duration);
  write_fig5_script(dir, runs);
  text += "\n";
  text += run_gnuplot(dir, "fig4_particles.gp");
  text += run_gnuplot(dir, "fig5_torque.gp");
  text +=
      "Pictures: figures/fig4_particles.png (cross-section, particles drawn at their radius), "
      "figures/fig5_torque.png; data: figures/<run>/*.csv.\n";
  return text;
}

std::string reproduce_table3(const ReproduceOptions& o) {
  const fs::path dir = o.out_dir / "table3";
  fs::create_directories(dir);
  CaseRunOptions target_run;
  target_run.threads = std::max(1, o.jobs * o.threads_per_job);
  target_run.progress = o.progress;
  bool computed = false;
  const json study = table3_study_document(o);
  const CaseResult original = cached_case_result(drum_spec(study, CoarseGraining::scg, 1.0), target_run, &computed);
  const identify::Curve target = original.curves.at("free_surface");
  write_curve_table(dir / "target_free_surface.csv",
                    curve_table(target, {"free surface of the original (s = 1) drum at the end time: Table 3 target"}));
  // The study reads the target just written (its relative paths resolve against this folder).
  const identify::StudySpec spec = identify::parse_study(study, dir);
  const auto model = make_model(spec.model_reference, spec.model_overrides, spec.base_dir);
  identify::EvaluationContext context;
  context.threads = o.threads_per_job;
  const identify::CurveSet initial_curves = model->evaluate({}, context);
  const double error_before = rms_surface_error(target, initial_curves.at("free_surface"));
  const auto cheap_model = make_cheap_level_model(spec, dir / "study");  // a study with a cheap level
  identify::RunOptions run = detail::study_run_options(o, dir / "study");
  run.cheap_model = cheap_model.get();
  const identify::StudyResult r = identify::run_study(spec, *model, run);
  const double error_after = rms_surface_error(target, r.best_curves.at("free_surface"));
  std::string t =
      "Table 3: parameters identified on the SCG s = 4 drum against the s = 1 free surface\n\n"
      "| Keyword | Variable | Initial value | Paper optimal | demfit optimal (the study's answer, its 95 % interval) "
      "|\n|---|---|---|---|---|\n";
  for (const identify::VariableSpec& v : spec.variables) {
    const bool wall = v.name.rfind("wall_", 0) == 0;
    t += std::string("| ") + (wall ? "*DEFINE_DE_TO_SURFACE_COUPLING" : "*CONTROL_DISCRETE_ELEMENT") + " | " +
         (wall ? v.name.substr(5) : v.name) + " | " + fmt("%g", v.initial) + " | " + paper_value(v.name) + " | " +
         table3_cell(r, v.name) + " |\n";
  }
  t += "\nSurface RMS error against the s = 1 target: " + fmt("%.3f", error_before) + " mm at the initial values, " +
       fmt("%.3f", error_after) + " mm after identification (ratio " + fmt("%.2f", error_after / error_before) + ").\n";
  t += replicate_text(*model, spec, r.best, error_before, error_after, target, o.quick ? 4 : 8, context);
  t += overlap_text(study, r.best, o);
  t += "Runs used: " + std::to_string(r.runs) + " (" + std::to_string(r.failed_runs) + " failed), " +
       std::to_string(r.iterations) + " iterations, wall time of this run " + fmt("%.0f", r.wall_seconds) +
       " s with " + std::to_string(o.jobs) +
       " parallel runs; the paper used 1,600 runs (16 x 100) at 390-4,688 s CPU each.\n";
  t += "The target (" + std::string(computed ? "computed now" : "read from cache") +
       ") is the s = 1 SCG run's free surface; our drum geometry is docs/spec.md 2.2's choice, so optimal values differ from "
       "the paper's.\n";
  return t;
}

}  // namespace demfit::cases
