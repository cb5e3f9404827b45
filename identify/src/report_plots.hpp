#pragma once
// Internal: the plots and the Markdown text of a study report.
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "demfit/identify/study_spec.hpp"
#include "demfit/identify/study_store.hpp"
#include "demfit/rbf_surrogate/bounds.hpp"

namespace demfit::identify::detail {

// Physical lower and upper edges of an iteration's subregion, per variable.
std::pair<std::vector<double>, std::vector<double>> region_band(const std::vector<rbf_surrogate::Variable>& variables,
                                                                const IterationRecord& iteration);
// Writes the PNG plots (needs the CSV files already in output_dir). Returns the image file names
// written and a warning ("" if all went well).
std::pair<std::vector<std::string>, std::string> write_plots(const StudySpec& spec,
                                                             const std::vector<EvaluationRecord>& runs,
                                                             const std::vector<IterationRecord>& iterations,
                                                             const EvaluationRecord* best,
                                                             const std::filesystem::path& output_dir);
// The status line of a study: finished (and why it stopped) or not finished.
std::string study_status(const std::optional<nlohmann::json>& result);
std::string report_markdown(const StudySpec& spec, const std::vector<EvaluationRecord>& runs,
                            const std::vector<IterationRecord>& iterations, const EvaluationRecord* best,
                            const std::optional<nlohmann::json>& result, const std::vector<std::string>& images);

}  // namespace demfit::identify::detail
