// demfit identify / report: the identification loop on a study file and reports rebuilt from a
// study store (`demfit export`: cmd_export.cpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands.hpp"
#include "cli_safety.hpp"
#include "demfit/cases/study_model.hpp"
#include "demfit/identify/external_model.hpp"
#include "demfit/identify/json_document.hpp"
#include "demfit/identify/safe_output.hpp"
#include "demfit/identify/store_lock.hpp"
#include "demfit/identify/study_answer.hpp"
#include "demfit/identify/study_preflight.hpp"
#include "demfit/identify/study_warnings.hpp"
#include "demfit/identify/relative_axis.hpp"
#include "demfit/identify/report.hpp"
#include "demfit/identify/study.hpp"
#include "demfit/identify/study_store.hpp"
#include "demfit/cases/model_factory.hpp"
#include "demfit/cases/parameter_table.hpp"
#if defined(DEMFIT_HAVE_SCALEOUT)
#include <iostream>

#include "demfit/scaleout/mpi_evaluator.hpp"
#endif

namespace demfit::apps {
namespace {

struct IdentifyOptions {
  std::string study_file;
  std::string out;
  int jobs = 1;
  int threads_per_job = 1;
  bool resume = false;
  bool no_plots = false;
  bool mpi = false;
  double run_timeout = 0.0;
};

void print_summary(const identify::StudySpec& spec, const identify::StudyResult& result,
                   const std::filesystem::path& out) {
  // "the answer's": with a final selection the answer need not be the lowest run (final_selection.hpp).
  std::printf("the answer's objective %.6g after %d runs (%d failed), %d iterations, %s\n", result.best_objective,
              result.runs, result.failed_runs, result.iterations,
              result.stop_reason.c_str());
  // The same interval as report.md, best_parameters.json and the export (reported_interval.hpp).
  for (const auto& v : spec.variables) {
    const auto found = result.intervals.find(v.name);
    std::printf("  %-12s %.9g", v.name.c_str(), result.best.at(v.name));
    if (found != result.intervals.end() && found->second.available)
      std::printf("  95 %% interval %s", identify::interval_text(found->second).c_str());
    // The study's warnings (stderr, report.md) say why and what would pin it.
    if (found != result.intervals.end() && !found->second.identifiable) std::printf("  not identifiable");
    std::printf("\n");
  }
  std::printf("results: %s\n", identify::printable((out / "report.md").string()).c_str());
}

#if defined(DEMFIT_HAVE_SCALEOUT)
// `mpirun -np K demfit identify STUDY.json --mpi`: every rank reads the study and builds the model
// (a shared file system is assumed); rank 0 runs the loop and owns the store, the others evaluate.
// Rank 0: the checks, the store and the loop. The evaluator exists before anything can fail, so
// its destructor always releases the workers and every rank can finalise normally.
void run_identify_rank0(const IdentifyOptions& o, identify::RunOptions options, const identify::StudySpec& parsed,
                        const identify::Model& model, scaleout::MpiSession& session) {
  scaleout::MpiEvaluatorOptions mpi_options;
  mpi_options.run_timeout_seconds = o.run_timeout;
  scaleout::MpiEvaluator evaluator(session, mpi_options);
  // As without MPI: every configuration error before anything is created, the
  // initial point evaluated on a worker rank (curve names, units, overlap).
  identify::OutputRequest request{identify::OutputKind::identify, cases::study_input_files(parsed, o.study_file)};
  std::optional<identify::StoreLock> lock;
  identify::claim_study_folder(options, request, lock, "--resume");
  options.resolved_model = cases::resolved_study_model(parsed);
  const identify::StudySpec spec = identify::preflight_study(parsed, model, evaluator, options);
  request.lock_held = lock.has_value();
  identify::prepare_output_folder(options.output_dir, request);
  if (!lock) lock.emplace(options.output_dir);
  options.evaluator = &evaluator;
  std::fprintf(stderr, "demfit: MPI: rank 0 runs the loop, %d worker rank(s) evaluate\n", session.size() - 1);
  const auto result = identify::run_study(spec, model, options);
  print_summary(spec, result, options.output_dir);
  std::fflush(stdout);
}

void run_identify_mpi(const IdentifyOptions& o, identify::RunOptions options) {
  int argc = 0;
  char** argv = nullptr;
  scaleout::MpiSession session(argc, argv);
  int status = 0;
  try {
    // Every rank reads the same study: a bad study fails on every rank alike, before any message.
    const identify::StudySpec parsed = identify::load_study_file(o.study_file);
    if (parsed.cheap_level)
      throw std::runtime_error(
          "study: cheap_level: a cheap level runs in one process; run the study without --mpi (with --jobs), or "
          "remove cheap_level");
    const auto model = cases::make_identify_model(parsed, options.output_dir);
    if (session.rank() != 0)
      scaleout::run_worker(*model, o.threads_per_job, parsed.seed);
    else
      run_identify_rank0(o, options, parsed, *model, session);
  } catch (const std::exception& e) {
    if (session.rank() == 0) std::cerr << "demfit: error: " << identify::printable(e.what()) << std::endl;
    status = 1;
  }
  // A normal finalisation, then the status: Open MPI 4.1's mpirun --enable-recovery reports an
  // aborted or unfinalised job as success (exit 0), but passes on a finalised rank's exit code.
  // After a lost worker, finish() exits at once with the status instead of waiting for it.
  session.finish(status);
  if (status != 0) std::exit(status);
}
#endif

// The report's warnings on stderr too, where a script's user sees them.
void print_warnings(const std::filesystem::path& db) {
  for (const auto& w : identify::study_diagnostics(identify::StudyStore::open_existing(db)).warnings)
    std::fprintf(stderr, "demfit: warning: %s\n", identify::printable(w).c_str());
}

void run_identify(const IdentifyOptions& o) {
  if (o.jobs < 1) throw std::runtime_error("--jobs: must be >= 1");
  if (o.threads_per_job < 1) throw std::runtime_error("--threads-per-job: must be >= 1");
  require_finite(o.run_timeout, "--run-timeout");
  if (o.run_timeout < 0) throw std::runtime_error("--run-timeout: must be >= 0 seconds (0 = automatic)");
  identify::RunOptions options;
  options.jobs = o.jobs;
  options.threads_per_job = capped_threads(o.threads_per_job, "--threads-per-job");
  options.resume = o.resume;
  options.plots = !o.no_plots;
  options.output_dir = o.out.empty()
                           ? std::filesystem::path(std::filesystem::path(o.study_file).stem().string() + "_results")
                           : std::filesystem::path(o.out);
  if (o.mpi) {
#if defined(DEMFIT_HAVE_SCALEOUT)
    run_identify_mpi(o, options);
    return;
#else
    throw std::runtime_error(
        "--mpi: this demfit was built without MPI; apt-get install libopenmpi-dev openmpi-bin "
        "and rebuild (scripts/build)");
#endif
  }
  // Every configuration error before anything is created: the study, the output folder rules, the
  // model, then one evaluation at the initial point (curve names, units, overlap).
  const identify::StudySpec spec = identify::load_study_file(o.study_file);
  const auto result = cases::run_study_file(spec, o.study_file, options, "--resume", "--out");
  print_summary(spec, result, options.output_dir);
  print_warnings(options.output_dir / "study.db");
}

}  // namespace

void register_identify(CLI::App& app) {
  auto options = std::make_shared<IdentifyOptions>();
  auto* identify = app.add_subcommand(
      "identify",
      "Identify model parameters from measured curves (study JSON, format in docs/study_format.md). "
      "Writes study.db (SQLite store), best_parameters.json, histories (CSV), plots (PNG), report.md and "
      "report.html (one self-contained page, plots embedded).");
  identify->add_option("study", options->study_file, "Study file (JSON)")->required()->check(CLI::ExistingFile);
  identify
      ->add_option("--out", options->out,
                   "Output folder (default: <study file stem>_results in the current folder); an existing one "
                   "only if identify made it (marker .demfit-output naming identify) or it is empty")
      ->check(non_empty_path());
  identify->add_option("--jobs", options->jobs,
                       "Simulations evaluated at once (default 1). Results do not depend on it.");
  identify->add_option("--threads-per-job", options->threads_per_job,
                       "OpenMP threads per simulation (default 1); keep jobs x threads-per-job <= cores");
  identify->add_flag("--resume", options->resume,
                     "Continue the study stored in <out>/study.db without repeating finished runs");
  identify->add_flag("--no-plots", options->no_plots, "Do not call gnuplot");
  identify->add_flag("--mpi", options->mpi,
                     "Spread evaluations over MPI ranks: mpirun --enable-recovery -np K demfit identify STUDY.json "
                     "--mpi (rank 0 runs the loop, K-1 ranks evaluate; same answer as --jobs)");
  identify->add_option("--run-timeout", options->run_timeout,
                       "With --mpi: seconds [s] before a silent worker is retired and its run retried elsewhere "
                       "(default 0 = automatic: max(120 s, 10 x the longest run so far))");
  identify->callback([options] { run_identify(*options); });

  auto report_db = std::make_shared<std::string>();
  auto report_out = std::make_shared<std::string>();
  auto report_no_plots = std::make_shared<bool>(false);
  auto* report =
      app.add_subcommand("report", "Rebuild the result files and report.md of a study from its study.db alone");
  report->add_option("store", *report_db, "Study store (study.db)")->required()->check(CLI::ExistingFile);
  report
      ->add_option("--out", *report_out,
                   "Output folder (default: the store's folder); never a folder holding another study's store or "
                   "results, or another command's output")
      ->check(non_empty_path());
  report->add_flag("--no-plots", *report_no_plots, "Do not call gnuplot");
  report->callback([report_db, report_out, report_no_plots] {
    const std::filesystem::path out =
        report_out->empty() ? std::filesystem::absolute(*report_db).parent_path() : std::filesystem::path(*report_out);
    // The folder may hold this study's store or report only, never another study's results.
    identify::OutputRequest request{identify::OutputKind::report, {*report_db}};
    request.study_store = *report_db;
    identify::check_output_folder(out, request);
    const auto store = identify::StudyStore::open_existing(*report_db);
    identify::prepare_output_folder(out, request);
    const auto summary = identify::write_report(store, out, !*report_no_plots);
    if (!summary.plot_warning.empty()) std::fprintf(stderr, "demfit: warning: %s\n", summary.plot_warning.c_str());
    for (const auto& w : identify::study_diagnostics(store).warnings)
      std::fprintf(stderr, "demfit: warning: %s\n", identify::printable(w).c_str());
    std::printf("%d files written to %s\n", summary.files_written, identify::printable(out.string()).c_str());
  });
  register_export(app);  // after report, as `demfit --help` lists them (cmd_export.cpp)
}

}  // namespace demfit::apps
