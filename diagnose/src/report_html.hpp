#pragma once
// Internal: report.html of a diagnosis (identify/report_html.hpp), written beside report.md.
#include <filesystem>
#include <string>

#include "demfit/diagnose/workflow.hpp"

namespace demfit::diagnose::detail {

// The page, top to bottom: the verdict and its summary, the candidate table (base and every re-fit
// with its criterion values), the plot of every target, then the whole of report.md (`markdown`).
void write_diagnosis_html(const Diagnosis& diagnosis, const std::string& markdown, const std::filesystem::path& out);

}  // namespace demfit::diagnose::detail
