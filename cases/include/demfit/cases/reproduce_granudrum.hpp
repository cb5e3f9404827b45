#pragma once
// `demfit reproduce granudrum [--quick] [--anchor]`: the shipped calibration
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
  ReproduceOptions base;             // out_dir, cases_dir, jobs, quick, resume
  std::filesystem::path study_file;  // empty = cases_dir/granudrum_calibration[_quick].json
  bool anchor = false;               // also run the source's published parameters at s = 1
  // With the anchor: the same parameters at these coarse-graining factors too (time step
  // s x the case's), each surface compared with the s = 1 one.
  std::vector<double> resolution_scales{4.0, 3.0, 2.0};
  // Merged into every anchor run's case (tests: a tiny drum); empty object = the real anchor.
  nlohmann::json anchor_overrides = nlohmann::json::object();
};

// Surface errors of one experiment's simulated profile against its photo target.
struct SurfaceError {
  std::string target;     // "<experiment>.<target>"
  double rms_mm = 0.0;    // RMS gap over the common x-range [mm]
  double area_mm2 = 0.0;  // differing area (area between the surfaces) [mm^2]
  // The gap simulated - photo split as imaging::profile_gap_parts does.
  double level_offset_mm = 0.0;       // mean gap [mm], > 0: simulated bed above the photo's
  double angle_difference_deg = 0.0;  // simulated minus photo surface angle [deg]
  double tilt_rms_mm = 0.0;           // RMS of the gap's linear trend [mm]
  double shape_rms_mm = 0.0;          // RMS left after level and tilt [mm]
};

// The report's paragraph on the experiments' level offsets, empty when there is nothing to say:
// when the simulated bed lies below the photo in one experiment and above it in another, and that
// level difference is larger than every experiment's shape part, it states that a shared fill
// cannot bring both levels to the photos' (more particles raise every experiment's bed; measured
// in docs/granudrum.md, "Where the 45 rpm gap lies").
std::string level_split_note(const std::vector<SurfaceError>& errors);

// Errors of every image target of `spec` against the curves of one design point (keys
// "<experiment>/<curve>"). Throws when a curve is missing or does not overlap its target.
std::vector<SurfaceError> surface_errors(const identify::StudySpec& spec, const identify::CurveSet& curves);

// For every image target: <dir>/granudrum_<experiment>_side_by_side.png (photo with its surface
// | the simulated bed below the best surface) and <dir>/granudrum_<experiment>_overlay.png (photo,
// photo surface red, simulated surface green). Returns the file names written (relative to dir).
std::vector<std::string> write_surface_pictures(const identify::StudySpec& spec, const identify::CurveSet& best,
                                                const std::filesystem::path& dir);

// One run of the published parameters: which experiment, at which coarse-graining factor, its
// wall time and OpenMP threads.
struct PublishedRun {
  std::string experiment;
  double scale = 1.0;
  double seconds = 0.0;
  int threads = 1;
};

// A coarse-grained surface of the published parameters against the s = 1 one and the photo.
struct ResolutionRow {
  std::string target;
  double scale = 1.0;
  double rms_vs_full_mm = 0.0, area_vs_full_mm2 = 0.0;
  double rms_vs_photo_mm = 0.0, area_vs_photo_mm2 = 0.0;
};

struct AnchorResult {
  std::vector<SurfaceError> errors;       // s = 1 against the photos, one per image target
  std::vector<ResolutionRow> resolution;  // one per image target and coarse factor
  std::vector<PublishedRun> runs;
  double wall_seconds = 0.0;  // all of them
};

// The Markdown section: identified values with intervals, runs and wall time, errors per speed,
// pictures, and (when given) the anchor's errors beside the calibrated ones.
std::string granudrum_report(const identify::StudySpec& spec, const identify::StudyResult& result,
                             const std::vector<SurfaceError>& calibrated, const AnchorResult& anchor,
                             const std::vector<std::string>& pictures);

// The source's published parameters (mu_s 0.561, mu_r 0.293, 29,185 particles) through demfit's
// Hertz law at s = 1 (plus options.anchor_overrides) for every experiment of the study, and at
// options.resolution_scales; the experiments side by side when options.base.jobs >= 2. Writes
// every run's curves as <out>/published_<experiment>_s<s>_<curve>.csv.
AnchorResult run_anchor(const identify::StudySpec& spec, const GranudrumOptions& options);

// The whole reproduction; writes <out>/study/..., pictures and <out>/granudrum.md; returns the text.
std::string reproduce_granudrum(const GranudrumOptions& options);

}  // namespace demfit::cases
