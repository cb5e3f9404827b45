#pragma once
// Internal: report.html of a study (report_html.hpp), written beside report.md.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "demfit/identify/study_spec.hpp"
#include "demfit/identify/study_store.hpp"

namespace demfit::identify::detail {

// The page, top to bottom: the study's answer (study_answer.hpp) with the identified values and
// their 95 % intervals, the status and the warnings; the measured vs simulated curves; the
// convergence history; the posterior pairs plot; then the whole of report.md (`markdown`).
// `images`: the plots written into output_dir; `store_folder`: the folder of the study store, where
// the study drew its posterior pairs plot.
void write_study_html(const StudySpec& spec, const std::vector<EvaluationRecord>& runs,
                      const std::vector<IterationRecord>& iterations, const std::optional<nlohmann::json>& result,
                      const std::filesystem::path& store, const std::vector<std::string>& images,
                      const std::string& markdown, const std::filesystem::path& output_dir);

}  // namespace demfit::identify::detail
