#pragma once
// Result files of a study, rebuilt from the study store alone (`demfit report STUDY.db`):
//   best_parameters.json   identified variables, all model parameters of the best run,
//                          objective, confidence half-widths, correlation, flags
//   evaluations.csv        one row per run: iteration, point, kind, status, objective,
//                          wall_s, variables (model units), error
//   iterations.csv         one row per iteration: subregion (centre, range per variable, model
//                          units), predicted optimum and objective, best objective, changes
//   best_<target>.csv      target and best simulated curve resampled at the target's x
//   target_<target>.png, objective_history.png, variable_<name>.png  (gnuplot, if installed)
//   report.md              ties them together
//   report.html            the same in one self-contained page, plots embedded (report_html.hpp)
// Every file is written through a temporary name and renamed.
#include <filesystem>

#include "demfit/identify/study_store.hpp"

namespace demfit::identify {

struct ReportSummary {
  int files_written = 0;
  bool plots_written = false;
  std::string plot_warning;  // why plots were skipped, if they were
};

ReportSummary write_report(const StudyStore& store, const std::filesystem::path& output_dir, bool plots = true);

}  // namespace demfit::identify
