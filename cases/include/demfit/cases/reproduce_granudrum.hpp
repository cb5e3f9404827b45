#pragma once
// `demfit reproduce granudrum [--quick] [--anchor]` (issue 14 items 4-5): the shipped calibration
// study on the GranuDrum MCC photos (cases/granudrum_calibration*.json) and its report.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "demfit/cases/reproduce.hpp"
#include "demfit/identify/study.hpp"
#include "demfit/identify/study_spec.hpp"

namespace demfit::cases {

struct GranudrumOptions {
  ReproduceOptions base;               // out_dir, cases_dir, jobs, quick, resume
  std::filesystem::path study_file;    // empty = cases_dir/granudrum_calibration[_quick].json
  bool anchor = false;                 // also run the source's published parameters at s = 1
  // Merged into every anchor run's case (tests: a tiny drum); empty object = the real anchor.
  nlohmann::json anchor_overrides = nlohmann::json::object();
};

// Surface errors of one experiment's simulated profile against its photo target.
struct SurfaceError {
  std::string target;       // "<experiment>.<target>"
  double rms_mm = 0.0;      // RMS gap over the common x-range [mm]
  double area_mm2 = 0.0;    // differing area (area between the surfaces) [mm^2]
};

// Errors of every image target of `spec` against the curves of one design point (keys
// "<experiment>/<curve>"). Throws when a curve is missing or does not overlap its target.
std::vector<SurfaceError> surface_errors(const identify::StudySpec& spec, const identify::CurveSet& curves);

// For every image target: <dir>/granudrum_<experiment>_side_by_side.png (photo with its surface
// | the simulated bed below the best surface) and <dir>/granudrum_<experiment>_overlay.png (photo,
// photo surface red, simulated surface green). Returns the file names written (relative to dir).
std::vector<std::string> write_surface_pictures(const identify::StudySpec& spec, const identify::CurveSet& best,
                                                const std::filesystem::path& dir);

// The Markdown section: identified values with intervals, runs and wall time, errors per speed,
// pictures, and (when given) the anchor's errors beside the calibrated ones.
std::string granudrum_report(const identify::StudySpec& spec, const identify::StudyResult& result,
                             const std::vector<SurfaceError>& calibrated, const std::vector<SurfaceError>& anchor,
                             const std::vector<std::string>& pictures, double anchor_seconds);

// The source's published parameters (mu_s 0.561, mu_r 0.293, 29,185 particles) through demfit's
// Hertz law at s = 1 (plus options.anchor_overrides) for every experiment of the study.
std::vector<SurfaceError> run_anchor(const identify::StudySpec& spec, const GranudrumOptions& options,
                                     double* wall_seconds);

// The whole reproduction; writes <out>/study/..., pictures and <out>/granudrum.md; returns the text.
std::string reproduce_granudrum(const GranudrumOptions& options);

}  // namespace demfit::cases
