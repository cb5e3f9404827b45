#pragma once
// Shared checks of the command line (issue #13): thread counts capped at the machine's cores,
// finite numeric options, the input files of a study (which no output may replace), and the
// removal of staging folders left by killed runs.
#include <filesystem>
#include <string>
#include <vector>

#include "demfit/identify/study_spec.hpp"

namespace demfit::apps {

// `requested` capped at the cores this process may use, with a note on stderr when capped.
int capped_threads(int requested, const std::string& option);
// Throws "<option>: must be a finite number" for NaN or infinity.
void require_finite(double value, const std::string& option);
// The study file, its target CSV files and its case file (when it is a file).
std::vector<std::filesystem::path> study_inputs(const identify::StudySpec& spec,
                                                const std::filesystem::path& study_file);
// Removes "<parent>/.<name>.partial-<pid>" staging folders of processes that no longer run.
void remove_stale_staging(const std::filesystem::path& target);

}  // namespace demfit::apps
