#pragma once
// The study-run settings every `demfit reproduce` step passes on from its options (jobs, threads
// per job, resume), with the step's own output folder. Internal to the cases library.
#include <filesystem>

#include "demfit/cases/reproduce.hpp"
#include "demfit/identify/study.hpp"

namespace demfit::cases::detail {

inline identify::RunOptions study_run_options(const ReproduceOptions& options,
                                              const std::filesystem::path& output_dir) {
  identify::RunOptions run;
  run.jobs = options.jobs;
  run.threads_per_job = options.threads_per_job;
  run.resume = options.resume;
  run.output_dir = output_dir;
  return run;
}

}  // namespace demfit::cases::detail
