// demfit reproduce table1|table2|table3|figures|all: the paper's studies, one command each.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>

#include "cli_safety.hpp"
#include "commands.hpp"
#include "demfit/identify/safe_output.hpp"
#include "demfit/cases/progress.hpp"
#include "demfit/cases/reproduce.hpp"
#include "demfit/cases/reproduce_granudrum.hpp"

#ifndef DEMFIT_DEFAULT_SOURCE_DIR
#define DEMFIT_DEFAULT_SOURCE_DIR ""
#endif

namespace demfit::apps {
namespace {

struct ReproduceArgs {
  std::string out = "results/reproduce";
  std::string data;
  int jobs = 2;
  int threads = 1;
  bool quick = false;
  bool resume = false;
  bool anchor = false;  // granudrum: also the source's parameters at s = 1
};

// The shipped data folder: --data, else ./data, else <executable>/../../data (build tree).
std::filesystem::path find_data_dir(const ReproduceArgs& a) {
  if (!a.data.empty()) return a.data;
  std::error_code error;
  const std::filesystem::path here("data");
  if (std::filesystem::exists(here / "pellet_pressure_volume_synthetic.csv", error)) return here;
  std::filesystem::path tree =
      std::filesystem::read_symlink("/proc/self/exe", error).parent_path().parent_path().parent_path();
  tree /= "data";
  if (std::filesystem::exists(tree / "pellet_pressure_volume_synthetic.csv", error)) return tree;
  return "data";
}

cases::ReproduceOptions options_of(const ReproduceArgs& a) {
  if (a.jobs < 1) throw std::runtime_error("--jobs must be >= 1");
  if (a.threads < 1) throw std::runtime_error("--threads must be >= 1");
  cases::ReproduceOptions o;
  o.out_dir = a.out;
  o.data_dir = find_data_dir(a);
  o.cases_dir = o.data_dir.parent_path() / "cases";  // shipped study files beside data/
  o.jobs = a.jobs;
  o.threads_per_job = capped_threads(a.threads, "--threads");
  o.quick = a.quick;
  o.resume = a.resume;
  // Progress of single long simulations (drum reference runs); studies print their own lines.
  static cases::ProgressPrinter printer(10.0);
  o.progress = printer.callback();
  // Never the working folder, a parent of it or a user's folder; created and marked.
  identify::prepare_output_folder(o.out_dir, {identify::OutputKind::reproduce, {}});
  return o;
}

using Step = std::string (*)(const cases::ReproduceOptions&);

void run_one(const ReproduceArgs& a, const char* name, Step step) {
  const cases::ReproduceOptions o = options_of(a);
  const std::string text = step(o);
  identify::write_file_atomically(o.out_dir / (std::string(name) + ".md"), text);
  std::cout << text;
}

void run_all(const ReproduceArgs& a) {
  const cases::ReproduceOptions o = options_of(a);
  const auto start = std::chrono::steady_clock::now();
  std::string report =
      "# demfit reproduce all" + std::string(a.quick ? " --quick" : "") +
      "\n\nThe paper's studies reproduced end to end (docs/spec.md section 2). Quick mode uses fewer runs and a "
      "cheaper drum (12.5 mm instead of 25 mm long, 0.25 s densification, 1 s of rotation); "
      "see docs/reproduce.md for the measured full-mode results and times.\n\n";
  const std::pair<const char*, Step> steps[] = {{"table2", cases::reproduce_table2},
                                                {"table1", cases::reproduce_table1},
                                                {"figures", cases::reproduce_figures},
                                                {"table3", cases::reproduce_table3}};
  for (const auto& [name, step] : steps) {
    std::cerr << "demfit reproduce all: " << name << "...\n";
    const auto t0 = std::chrono::steady_clock::now();
    std::string text;
    try {
      text = step(o);
    } catch (const std::exception& e) {
      text = std::string("**") + name + " failed:** " + identify::printable(e.what()) + "\n";
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::cout << text << '\n';
    char timing[96];
    std::snprintf(timing, sizeof timing, "\n_%s: %.0f s wall time._\n\n", name, seconds);
    report += "## " + std::string(name) + "\n\n" + text + timing;
    identify::write_file_atomically(o.out_dir / "report.md", report);  // partial report survives a later failure
  }
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  char line[96];
  std::snprintf(line, sizeof line, "Total wall time: %.0f s.\n", total);
  report += line;
  identify::write_file_atomically(o.out_dir / "report.md", report);
  std::cout << line << "report: " << (o.out_dir / "report.md").string() << '\n';
}

// demfit reproduce granudrum: the shipped GranuDrum calibration (cases/granudrum_calibration*.json).
void run_granudrum(const ReproduceArgs& a) {
  cases::GranudrumOptions g;
  g.base = options_of(a);
  g.anchor = a.anchor;
  std::cout << cases::reproduce_granudrum(g) << "report: " << (g.base.out_dir / "granudrum.md").string() << '\n';
}

}  // namespace

void register_reproduce(CLI::App& app) {
  auto args = std::make_shared<ReproduceArgs>();
  auto* cmd = app.add_subcommand("reproduce",
                                 "Reproduce the paper's tables and figures (docs/spec.md 2). Writes into --out; settled fills "
                                 "and drum targets are cached in $DEMFIT_CACHE_DIR (default ~/.cache/demfit).");
  cmd->require_subcommand(1);
  auto add_common = [args](CLI::App* sub) {
    sub->add_option("--out", args->out, "results folder (default results/reproduce)")->check(non_empty_path());
    sub->add_option("--data", args->data, "folder of the shipped data (default: ./data or the source tree's data/)");
    sub->add_option("--jobs", args->jobs, "simulations run at once (default 2)");
    sub->add_option("--threads", args->threads, "OpenMP threads per simulation (default 1)");
    sub->add_flag("--quick", args->quick,
                  "fewer runs and a cheaper drum: 12.5 mm long (half), 0.25 s densification, 1 s of rotation "
                  "(minutes instead of an hour)");
    sub->add_flag("--resume", args->resume, "continue identification studies found in --out");
  };
  struct Entry {
    const char* name;
    const char* help;
    Step step;
  };
  const Entry entries[] = {
      {"table1", "Table 1: K_bulk, and NORMK/SHEARK identified from the synthetic pellet curve",
       cases::reproduce_table1},
      {"table2", "Table 2: SCG and CVF coarse-graining rows for s = 1, 2, 4 (with the CVF radius note)",
       cases::reproduce_table2},
      {"figures", "Figs. 4-5: drum particle pictures at the end time and torque histories, s = 1, 2, 4, SCG and CVF",
       cases::reproduce_figures},
      {"table3", "Table 3: 9 drum parameters of SCG s = 4 identified against the s = 1 free surface",
       cases::reproduce_table3}};
  for (const Entry& e : entries) {
    auto* sub = cmd->add_subcommand(e.name, e.help);
    add_common(sub);
    const char* name = e.name;
    Step step = e.step;
    sub->callback([args, name, step] { run_one(*args, name, step); });
  }
  auto* granudrum = cmd->add_subcommand(
      "granudrum",
      "GranuDrum MCC photos (data/granudrum_mcc): calibrate sliding friction, rolling friction and the particle count "
      "jointly on 15 and 45 rpm (cases/granudrum_calibration.json; --quick: granudrum_calibration_quick.json); writes "
      "granudrum.md, the study and side-by-side/overlay PNGs into --out (default results/granudrum)");
  add_common(granudrum);
  granudrum->add_flag("--anchor", args->anchor,
                      "also run the source's published parameters (mu_s 0.561, mu_r 0.293, 29,185 particles) at s = 1 "
                      "at both speeds (about 10+ minutes per speed) and report their surface errors");
  granudrum->callback([args, granudrum] {
    if (granudrum->get_option("--out")->count() == 0) args->out = "results/granudrum";
    run_granudrum(*args);
  });
  auto* all = cmd->add_subcommand("all", "Everything above into one folder with report.md");
  add_common(all);
  all->callback([args] { run_all(*args); });
}

}  // namespace demfit::apps
