// demfit simulate CASE.json: runs one case and writes its curves (CSV with units in the header),
// the resolved case JSON, a summary and optional VTK snapshots, all-or-nothing.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli_safety.hpp"
#include "commands.hpp"
#include "demfit/identify/safe_output.hpp"
#include "demfit/cases/case_output.hpp"
#include "demfit/cases/case_runner.hpp"
#include "demfit/cases/case_spec.hpp"
#include "demfit/cases/parameter_table.hpp"

namespace demfit::apps {
namespace {

struct SimulateOptions {
  std::string case_file;
  std::vector<std::string> settings;
  std::string out;
  int threads = 1;
  double noise = 0.0;
  std::string seed = "1";
  std::vector<double> snapshots;
};

// Noise seeds: curve k uses seed + k, which must not wrap.
constexpr unsigned long long kMaxSeed = 1ull << 62;

// The latest time the measured stage can end: the drum's rotation time; the pellet's piston stroke
// at its speed (loading, and as long again when it unloads). A snapshot time after it would never
// be written.
void check_snapshot_times(const cases::CaseSpec& spec) {
  double end = 0.0;
  const char* what = "";
  switch (spec.kind) {  // exhaustive (case_registry.hpp)
    case cases::CaseKind::pellet_compression:
      end = spec.pellet.max_travel / spec.pellet.piston_speed * (spec.pellet.unload ? 2.0 : 1.0);
      what = ", the longest piston stroke: max_travel / piston_speed";
      break;
    case cases::CaseKind::rotary_drum:
      end = spec.drum.duration;
      what = ": drum.duration";
      break;
    case cases::CaseKind::mesh_container:
      end = spec.mesh_container.duration;
      what = ": mesh_container.duration";
      break;
  }
  for (double t : spec.output.snapshot_times) {
    if (t <= end) continue;
    char text[240];
    std::snprintf(text, sizeof text,
                  "--snapshots / output.snapshot_times: %.6g s is after the end of the measured stage (%.6g s%s); "
                  "give times from 0 to %.6g s",
                  t, end, what, end);
    throw std::runtime_error(text);
  }
}

// The --set settings: identified parameters into `parameters` (they act on the measured stage
// only; the cached fill is shared), any other dotted field into the case document.
void apply_settings(const std::vector<std::string>& settings, nlohmann::json& document,
                    identify::ParameterSet& parameters) {
  for (const std::string& s : settings) {
    const auto eq = s.find('=');
    const std::string name = s.substr(0, eq == std::string::npos ? 0 : eq);
    if (eq != std::string::npos && !cases::parameter_path(name).empty()) {
      parameters[name] = parse_number(s.substr(eq + 1), "--set " + name);
    } else {
      // A value that starts like a number must be one number ("0,1" and "1e999" are errors); words,
      // true/false and JSON arrays or objects go to the case as they are.
      const std::string value = eq == std::string::npos ? "" : s.substr(eq + 1);
      if (!value.empty() && value.find_first_of("0123456789+-.") == 0) parse_number(value, "--set " + name);
      cases::apply_setting(document, s);
    }
  }
}

// Every identified parameter used in the measured stage, not only the --set ones.
identify::ParameterSet evaluated_parameters(const cases::CaseSpec& spec, identify::ParameterSet evaluated) {
  const nlohmann::json base = cases::to_json(spec);
  for (const std::string& name : cases::parameter_names()) {
    if (evaluated.count(name)) continue;
    const std::string path = cases::parameter_path(name);
    const auto dot = path.find('.');
    // Parameters of the other contact law or fill form are absent from the resolved case.
    const std::string section = path.substr(0, dot), key = path.substr(dot + 1);
    if (!base.contains(section) || !base[section].contains(key) || !base[section][key].is_number()) continue;
    evaluated[name] = base[section][key].get<double>();
  }
  return evaluated;
}

void run_simulate(const SimulateOptions& o) {
  // Parse everything before any output exists (bad input leaves nothing behind).
  nlohmann::json document = cases::read_case_json(o.case_file);
  identify::ParameterSet parameters;
  apply_settings(o.settings, document, parameters);
  if (!o.snapshots.empty()) document["output"]["snapshot_times"] = o.snapshots;
  const cases::CaseSpec spec = cases::parse_case(document, std::filesystem::path(o.case_file).parent_path());
  check_snapshot_times(spec);
  const unsigned long long seed = parse_count(o.seed, "--seed", kMaxSeed);
  if (o.threads < 1) throw std::runtime_error("--threads must be >= 1");
  if (!(o.noise >= 0.0) || !std::isfinite(o.noise))
    throw std::runtime_error("--noise must be a finite number >= 0 (relative to max|y| of each curve)");
  const std::filesystem::path out = o.out.empty()
                                        ? std::filesystem::path("results") / std::filesystem::path(o.case_file).stem()
                                        : std::filesystem::path(o.out);
  // The output folder replaces an existing one only if simulate made it: never the working folder,
  // a parent of it, a folder holding the case file, a plain file, a user folder or another command's.
  identify::OutputRequest request{identify::OutputKind::simulate, {o.case_file}};
  identify::check_replaceable_folder(out, request);
  remove_stale_staging(out);
  const int threads = capped_threads(o.threads, "--threads");
  // The staging folder, marked, before the run: a folder that cannot be written fails now, not
  // after the simulation.
  CreatedParents parents(out);
  cases::StagedDirectory staged(out);
  try {
    identify::mark_output_folder(staged.path(), identify::OutputKind::simulate);
  } catch (const std::exception& e) {
    throw std::runtime_error("--out: cannot write beside " + identify::quote_path(out) + " (" + e.what() +
                             "); give a folder in a writable place");
  }
  cases::ProgressPrinter progress(spec.output.progress_interval);
  cases::CaseRunOptions run_options;
  run_options.threads = threads;
  run_options.progress = progress.callback();
  if (!spec.output.snapshot_times.empty()) {
    run_options.snapshot_dir = staged.path() / "snapshots";
    std::filesystem::create_directories(run_options.snapshot_dir);
  }
  const cases::CaseResult result = cases::run_case(spec, parameters, run_options);
  progress.finish();
  const identify::ParameterSet evaluated = evaluated_parameters(spec, parameters);
  nlohmann::json resolved = cases::to_json(spec);
  resolved["description"] =
      spec.description +
      (parameters.empty()
           ? ""
           : " [run with --set parameters: see summary.txt; the fill uses the values below, except radius_spread, "
             "which is applied to the fill too]");
  cases::write_case_result(staged.path(), result, resolved, evaluated, {o.noise, seed});
  identify::check_replaceable_folder(out, request);  // still replaceable after the run (another demfit?)
  staged.commit();
  parents.keep();
  std::cout << "demfit simulate: " << identify::printable(o.case_file) << " -> " << identify::printable(out.string())
            << '\n'
            << cases::format_summary(result);
  if (o.noise > 0.0) std::cout << "\ncurves are SYNTHETIC: noise " << o.noise << " x max|y|, seed " << seed << '\n';
}

}  // namespace

void register_simulate(CLI::App& app) {
  auto options = std::make_shared<SimulateOptions>();
  auto* cmd = app.add_subcommand(
      "simulate",
      "Run one case (pellet_compression, rotary_drum or mesh_container) and write its curves.\n"
      "Outputs in --out: <curve>.csv (header names carry units: volume_cm3, pressure_MPa, time_s,\n"
      "torque_Nm, x_mm, height_mm, heap_angle_deg, discharged_mass_kg), history/particle tables, case_resolved.json "
      "(all defaults\n"
      "filled in), summary.txt, snapshots/*.vtk when requested. Case files are JSON in SI units\n"
      "(m, kg, s, Pa; rpm named). Settled fills are cached in $DEMFIT_CACHE_DIR (default\n"
      "~/.cache/demfit). Nothing is written when the input is bad or the run fails.\n"
      "Defaults (docs/cases.md): contact NORMK 0.01, SHEARK 2/7, other contact values 0, FRICD = FRICS, wall SFP 1;\n"
      "time step automatic (0.15 x 2 pi sqrt(m*/k) and dem_core's packing bounds). Pellet: 1450 pellets in a\n"
      "36 mm x 64 mm cylinder, piston 0.05 m/s to 3 MPa (30 mm stroke limit), 60 curve points. Drum: 100 mm x 25 mm,\n"
      "60 rpm for 3 s, fill 30 % at phi 0.64, SCG s = 1, free surface averaged over the last 0.1 s (5 snapshots).");
  cmd->add_option("case", options->case_file, "case JSON file (e.g. cases/pellet_compression.json)")->required();
  cmd->add_option("--set", options->settings,
                  "override: name=value. Identified parameters (listed below with unit, valid range and contact "
                  "law) act on the measured stage; those marked \"changes the fill\" make a new fill, cached per "
                  "value; any other dotted case field (e.g. pellet.piston_speed=0.1 [m/s]) edits the case")
      ->take_all();
  cmd->add_option("--out", options->out,
                  "output folder (default: results/<case file stem>); replaced if it exists and demfit created it "
                  "(marker file .demfit-output naming simulate); never the working folder, a parent of it, a folder of "
                  "another command, or a folder holding the case")
      ->check(non_empty_path());
  cmd->add_option("--threads", options->threads, "OpenMP threads of the simulation (default 1)");
  cmd->add_option("--noise", options->noise,
                  "add seeded Gaussian noise to the written curves, sigma = NOISE x max|y| (default 0 = none); "
                  "the CSV files are then labelled SYNTHETIC");
  cmd->add_option("--seed", options->seed,
                  "noise seed, a whole number from 0 to 2^62 (default 1); curve k in name order uses seed + k");
  cmd->add_option("--snapshots", options->snapshots,
                  "VTK snapshot times [s] from the start of the measured stage, at most its end (drum: "
                  "drum.duration; pellet: max_travel / piston_speed) (default: none)")
      ->delimiter(',');
  cmd->footer("Identified parameters for --set (docs/parameters.md, `demfit parameters`):\n" +
              cases::parameter_help_text());
  cmd->callback([options] { run_simulate(*options); });
}

}  // namespace demfit::apps
