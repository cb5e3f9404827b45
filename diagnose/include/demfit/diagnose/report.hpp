#pragma once
// Writes the diagnosis: report.md (criterion values of every candidate, gap before/after overall
// and per region, residual tests before/after), diagnosis.json (the same numbers) and
// diagnosis.png (target, base fit, augmented fit, residuals; via a gnuplot process, skipped with
// a warning if gnuplot is missing), and report.html: the same in one self-contained page with the
// plots embedded (identify/report_html.hpp).
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "demfit/diagnose/workflow.hpp"

namespace demfit::diagnose {

nlohmann::json to_json(const Diagnosis& diagnosis);
std::string markdown_report(const Diagnosis& diagnosis);
// Writes the three files into `out` (created). Returns warnings (e.g. no gnuplot), one per line.
// The fitted curves are data + residual at the data abscissae (no model evaluation needed).
std::string write_diagnosis(const Diagnosis& diagnosis, const std::filesystem::path& out, bool plots);

}  // namespace demfit::diagnose
