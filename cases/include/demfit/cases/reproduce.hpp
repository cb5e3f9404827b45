#pragma once
// `demfit reproduce ...`: the paper's studies end to end. Each function writes its
// files into `out_dir` (created) and returns the Markdown text it also prints.
#include <filesystem>
#include <string>

#include "demfit/cases/progress.hpp"

namespace demfit::cases {

struct ReproduceOptions {
  std::filesystem::path out_dir;    // results folder of this reproduction
  std::filesystem::path data_dir;   // shipped data (data/ of the source tree)
  std::filesystem::path cases_dir;  // shipped case files (cases/ of the source tree)
  int jobs = 2;                     // simulations run at once
  int threads_per_job = 1;          // OpenMP threads per simulation
  bool quick = false;               // fewer runs, shorter drum time
  bool resume = false;              // continue studies found in out_dir
  ProgressCallback progress;        // simulation progress (single runs only)
};

// Table 1: identify NORMK and SHEARK of the pellet case from the shipped synthetic curve,
// starting from the LS-DYNA defaults; paper vs identified values with CIs and runs used.
std::string reproduce_table1(const ReproduceOptions& options);

// Table 2 for s = 1, 2, 4 (no simulation).
std::string reproduce_table2(const ReproduceOptions& options);

// Figs. 4-5: drum runs at s = 1, 2, 4 for SCG and CVF; particle pictures at the end time and
// torque histories (PNG via gnuplot when available, plus the CSV data).
std::string reproduce_figures(const ReproduceOptions& options);

// Table 3: identify the 9 variables on the SCG s = 4 drum against the s = 1 free surface.
std::string reproduce_table3(const ReproduceOptions& options);

}  // namespace demfit::cases
