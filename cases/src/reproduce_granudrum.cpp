// `demfit reproduce granudrum`: calibrate sliding friction, rolling friction
// and the fill amount jointly on the 15 and 45 rpm GranuDrum photos, then report the photo and
// the best simulated surface side by side and overlaid, the identified values with intervals, the
// runs and wall time, and the surface errors per speed (RMS gap in mm, differing area in mm^2).
#include "demfit/cases/reproduce_granudrum.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <future>
#include <mutex>
#include <stdexcept>

#include "demfit/identify/curve_io.hpp"
#include "demfit/identify/report_html.hpp"
#include "demfit/identify/safe_output.hpp"
#include "demfit/cases/case_runner.hpp"
#include "demfit/cases/case_spec.hpp"
#include "demfit/cases/model_factory.hpp"
#include "demfit/cases/study_model.hpp"
#include "demfit/imaging/image.hpp"
#include "demfit/imaging/overlay.hpp"
#include "demfit/imaging/profile_metrics.hpp"
#include "reproduce_study.hpp"
#include "number_text.hpp"

namespace demfit::cases {
namespace {

namespace fs = std::filesystem;

// A curve x_mm, z_mm (drum frame) as an imaging profile in metres.
imaging::SurfaceProfile profile_of(const identify::Curve& curve, double compared_radius) {
  imaging::SurfaceProfile p = imaging::profile_from_mm(curve.x, curve.y, "granudrum report: free-surface curve");
  p.compared_radius = compared_radius;
  return p;
}

const identify::Curve& curve_for(const identify::CurveSet& curves, const identify::TargetSpec& target) {
  const auto found = curves.find(target.curve);
  if (found == curves.end()) throw std::runtime_error("granudrum report: no simulated curve '" + target.curve + "'");
  return found->second;
}

// The source's calibrated values (data/granudrum_mcc/README.md): one definition for the runs and the report.
const identify::ParameterSet& published_parameters() {
  static const identify::ParameterSet values{{"frics", 0.561}, {"fricr", 0.293}, {"particle_count", 29185.0}};
  return values;
}

std::string scale_label(double scale) { return fmt("%g", scale); }

std::string experiment_of(const identify::TargetSpec& t) { return t.experiment.empty() ? t.name : t.experiment; }

// The simulated bed as a picture: light background, the material below the simulated surface
// (inside the compared circle; the surface's end heights held beyond its ends) dark, the compared
// circle outlined.
imaging::RgbImage simulated_bed(int pixels, const imaging::DrumFrame& frame, const imaging::SurfaceProfile& sim) {
  imaging::RgbImage image{pixels, pixels, std::vector<std::uint8_t>(3 * pixels * pixels, 235)};
  const double r2 = sim.compared_radius * sim.compared_radius;
  for (int row = 0; row < pixels; ++row) {
    const double z = imaging::pixel_z(row, pixels, frame.diameter);
    for (int col = 0; col < pixels; ++col) {
      const double x = imaging::pixel_x(col, pixels, frame.diameter);
      if (x * x + z * z > r2) continue;
      std::size_t k = 1;
      while (k + 1 < sim.x.size() && sim.x[k] < x) ++k;
      // Beyond the profile's ends its end heights are held (as the metrics do).
      const double t = std::clamp((x - sim.x[k - 1]) / std::max(1e-12, sim.x[k] - sim.x[k - 1]), 0.0, 1.0);
      if (z > sim.z[k - 1] + t * (sim.z[k] - sim.z[k - 1])) continue;
      std::fill_n(image.rgb.begin() + 3 * (static_cast<std::size_t>(row) * pixels + col), 3, std::uint8_t{70});
    }
  }
  imaging::SurfaceProfile no_line = sim;
  no_line.x.clear();
  no_line.z.clear();
  // draw_overlay of an empty profile on a white picture gives the circle only; copy its blue pixels.
  imaging::GreyImage white{pixels, pixels, std::vector<float>(static_cast<std::size_t>(pixels) * pixels, 1.0f), ""};
  const imaging::RgbImage circle = imaging::draw_overlay(white, frame, no_line);
  for (std::size_t k = 0; k < circle.rgb.size(); k += 3)
    if (circle.rgb[k + 2] == 255 && circle.rgb[k] != 255) std::copy_n(circle.rgb.begin() + k, 3, image.rgb.begin() + k);
  imaging::draw_profile(image, frame, sim, 20, 160, 40);
  return image;
}

imaging::RgbImage side_by_side(const imaging::RgbImage& left, const imaging::RgbImage& right) {
  const int gap = 8;
  imaging::RgbImage out{left.width + gap + right.width, std::max(left.height, right.height), {}};
  out.rgb.assign(3 * static_cast<std::size_t>(out.width) * out.height, 255);
  auto blit = [&out](const imaging::RgbImage& in, int x0) {
    for (int row = 0; row < in.height; ++row)
      std::copy_n(in.rgb.begin() + 3 * static_cast<std::size_t>(row) * in.width, 3 * in.width,
                  out.rgb.begin() + 3 * (static_cast<std::size_t>(row) * out.width + x0));
  };
  blit(left, 0);
  blit(right, left.width + gap);
  return out;
}

std::string error_row(const SurfaceError& e) { return fmt("%.2f", e.rms_mm) + " | " + fmt("%.0f", e.area_mm2); }

}  // namespace

std::vector<SurfaceError> surface_errors(const identify::StudySpec& spec, const identify::CurveSet& curves) {
  std::vector<SurfaceError> out;
  for (const auto& target : spec.targets) {
    if (!target.image) continue;
    const double radius = (1.0 - target.image->margin) * 0.5 * target.image->diameter;
    const auto photo = profile_of(target.data, radius);
    const auto sim = profile_of(curve_for(curves, target), radius);
    const imaging::ProfileGapParts parts = imaging::profile_gap_parts(sim, photo);
    out.push_back({target.name, 1e3 * parts.rms, 1e6 * imaging::profile_differing_area(sim, photo),
                   1e3 * parts.level_offset, parts.angle_difference_deg, 1e3 * parts.tilt_rms, 1e3 * parts.shape_rms});
  }
  return out;
}

std::vector<std::string> write_surface_pictures(const identify::StudySpec& spec, const identify::CurveSet& best,
                                                const fs::path& dir) {
  std::vector<std::string> files;
  for (const auto& target : spec.targets) {
    if (!target.image) continue;
    fs::path file = target.image->file;
    if (file.is_relative()) file = spec.base_dir / file;
    const imaging::GreyImage photo = imaging::read_grey_image(file);
    const imaging::DrumFrame frame{target.image->diameter};
    const double radius = (1.0 - target.image->margin) * 0.5 * frame.diameter;
    const auto measured = profile_of(target.data, radius);
    const auto simulated = profile_of(curve_for(best, target), radius);
    const imaging::RgbImage photo_view = imaging::draw_overlay(photo, frame, measured);
    const std::string stem = "granudrum_" + experiment_of(target);
    identify::write_file_atomically(
        dir / (stem + "_side_by_side.png"),
        imaging::encode_png(side_by_side(photo_view, simulated_bed(photo.width, frame, simulated))));
    imaging::RgbImage overlay = photo_view;
    imaging::draw_profile(overlay, frame, simulated, 20, 160, 40);
    identify::write_file_atomically(dir / (stem + "_overlay.png"), imaging::encode_png(overlay));
    files.push_back(stem + "_side_by_side.png");
    files.push_back(stem + "_overlay.png");
  }
  return files;
}

// The published parameters at every resolution run: each run's wall time, and how far each
// coarse-grained surface lies from the s = 1 one (the measurement behind the studies' choice of s).
std::string anchor_section(const AnchorResult& published) {
  std::string t = "\nPublished parameters run in demfit (" + fmt("%.0f", published.wall_seconds) +
                  " s wall time in all; the speeds side by side, one thread per run):\n\n"
                  "| experiment | s | run wall time [s] | threads |\n|---|---|---|---|\n";
  for (const auto& r : published.runs)
    t += "| " + r.experiment + " | " + scale_label(r.scale) + " | " + fmt("%.0f", r.seconds) + " | " +
         std::to_string(r.threads) + " |\n";
  if (published.resolution.empty()) return t;
  t +=
      "\nResolution: the same parameters at coarse-graining factor s (time step s x the case's), "
      "surface against the s = 1 surface and against the photo:\n\n"
      "| target | s | vs s = 1: RMS [mm] | area [mm²] | vs photo: RMS [mm] | area [mm²] |\n|---|---|---|---|---|---|\n";
  for (const auto& r : published.resolution)
    t += "| " + r.target + " | " + scale_label(r.scale) + " | " + fmt("%.2f", r.rms_vs_full_mm) + " | " +
         fmt("%.0f", r.area_vs_full_mm2) + " | " + fmt("%.2f", r.rms_vs_photo_mm) + " | " +
         fmt("%.0f", r.area_vs_photo_mm2) + " |\n";
  return t;
}

std::string level_split_note(const std::vector<SurfaceError>& errors) {
  if (errors.size() < 2) return "";
  const auto [low, high] = std::minmax_element(
      errors.begin(), errors.end(), [](const auto& a, const auto& b) { return a.level_offset_mm < b.level_offset_mm; });
  const double spread = high->level_offset_mm - low->level_offset_mm;
  double largest_shape = 0.0;
  for (const auto& e : errors) largest_shape = std::max(largest_shape, e.shape_rms_mm);
  if (!(low->level_offset_mm < 0.0 && high->level_offset_mm > 0.0 && spread > largest_shape)) return "";
  return "\nLevels: the simulated bed lies " + fmt("%.2f", -low->level_offset_mm) + " mm below the photo's in " +
         low->target + " and " + fmt("%.2f", high->level_offset_mm) + " mm above it in " + high->target + ": " +
         fmt("%.2f", spread) +
         " mm apart, more than any experiment's shape part. The experiments share the fill, and more or fewer "
         "particles move every experiment's bed the same way, so the variables that set the fill cannot bring both "
         "levels to the photos': the model's bed changes its level between these experiments differently from the "
         "measured one (in a drum, e.g. how much the flowing layer dilates as the speed rises). The calibration can "
         "only split this difference between the experiments; how it splits it is the objective's choice (the "
         "targets' weights).\n";
}

namespace {

// How the photos enter the objective: a study chooses how the speeds share a misfit that no
// variable removes (the level note), so the report states it.
std::string objective_text(const identify::StudySpec& spec) {
  std::string t = "Objective: the sum over the photos of weight x (mean gap / scale)^2 (metric profile_area);";
  for (const auto& target : spec.targets) {
    if (!target.image) continue;
    t += " " + target.name + ": weight " + fmt("%g", target.weight) + ", scale " +
         (target.scale > 0.0 ? fmt("%g mm", target.scale) : std::string("max |z| of the photo profile")) + ";";
  }
  t.back() = '.';
  return t + "\n";
}

std::string gap_rows(const std::vector<SurfaceError>& errors, const std::string& who) {
  std::string t;
  for (const auto& e : errors)
    t += "| " + e.target + " | " + who + " | " + fmt("%+.2f", e.level_offset_mm) + " | " +
         fmt("%+.1f", e.angle_difference_deg) + " | " + fmt("%.2f", e.tilt_rms_mm) + " | " +
         fmt("%.2f", e.shape_rms_mm) + " |\n";
  return t;
}

// Where each gap lies: level, angle and shape (imaging::profile_gap_parts), then the level note.
std::string gap_section(const std::vector<SurfaceError>& calibrated, const std::vector<SurfaceError>& anchor) {
  std::string t =
      "\nWhere the gap lies (simulated minus photo over the common x-range; RMS² = level² + tilt² + shape²):\n\n"
      "| target | run | level offset [mm] | angle difference [deg] (least-squares lines over the common range) "
      "| tilt RMS [mm] | shape RMS [mm] |\n"
      "|---|---|---|---|---|---|\n";
  t += gap_rows(calibrated, "demfit calibrated");
  t += gap_rows(anchor, "source's parameters, s = 1");
  return t + level_split_note(calibrated);
}

}  // namespace

std::string granudrum_report(const identify::StudySpec& spec, const identify::StudyResult& r,
                             const std::vector<SurfaceError>& calibrated, const AnchorResult& published,
                             const std::vector<std::string>& pictures) {
  const std::vector<SurfaceError>& anchor = published.errors;
  std::string t = "## GranuDrum MCC: calibration on the 15 and 45 rpm photos (" + spec.name + ")\n\n";
  t += "| variable | identified (best run) | 95 % interval | least-squares estimate | note |\n|---|---|---|---|---|\n";
  for (const auto& v : spec.variables) {
    const auto best = r.best.find(v.name);
    const auto interval = r.intervals.find(v.name);  // the same interval as report.md (reported_interval.hpp)
    const auto ls = r.least_squares_estimate.find(v.name);
    const bool known = interval != r.intervals.end();
    const std::string note = known && !interval->second.identifiable ? "not identifiable" : "";
    t += "| " + v.name + " | " + (best != r.best.end() ? fmt("%.6g", best->second) : "?") + " | " +
         (known ? identify::interval_text(interval->second) : std::string("n/a")) + " | " +
         (ls != r.least_squares_estimate.end() ? fmt("%.6g", ls->second) : "n/a") + " | " + note + " |\n";
  }
  t += "\nSource's published values:";
  for (const auto& [name, value] : published_parameters()) t += " " + name + " " + fmt("%g", value);
  t += " (50 mL).\n\n";
  t += "Runs: " + std::to_string(r.runs) + " evaluations (each = both speeds; " + std::to_string(r.failed_runs) +
       " failed), " + std::to_string(r.iterations) + " iterations, wall time " + fmt("%.0f", r.wall_seconds) +
       " s.\n\n";
  t += objective_text(spec) + "\n";
  t += "| target | demfit calibrated RMS [mm] | differing area [mm²] |";
  t += anchor.empty() ? "\n|---|---|---|\n"
                      : " source's parameters at s = 1: RMS [mm] | differing area [mm²] |\n|---|---|---|---|---|\n";
  for (std::size_t i = 0; i < calibrated.size(); ++i) {
    t += "| " + calibrated[i].target + " | " + error_row(calibrated[i]);
    if (i < anchor.size()) t += " | " + error_row(anchor[i]);
    t += " |\n";
  }
  t += gap_section(calibrated, anchor);
  if (!anchor.empty()) t += anchor_section(published);
  t += "\nPictures (photo with its surface in red, compared circle in blue; simulated surface in green):\n\n";
  for (const auto& p : pictures) t += "![" + p + "](" + p + ")\n";
  return t;
}

namespace {

// The published parameters through one experiment's case at coarse-graining factor `scale`
// (1 = the original particles with the case's own time step, the source's 1e-5 s; s > 1 with
// s times that step, the studies' rule: the Hertz stable step grows with the radius).
identify::CurveSet run_published(const identify::StudySpec& spec, const identify::ExperimentSpec& experiment,
                                 const GranudrumOptions& options, double scale, const ProgressCallback& progress) {
  nlohmann::json overrides = experiment.model_overrides;
  if (overrides.is_object()) overrides.erase("time_step");  // a study's coarse step would be unstable at s = 1
  overrides.merge_patch({{"drum", {{"scale_factor", 1.0}}}});
  overrides.merge_patch(options.anchor_overrides);
  CaseSpec run_case_spec = resolve_case(experiment.model_reference, overrides, spec.base_dir);
  if (scale != 1.0) {
    overrides.merge_patch(
        {{"drum", {{"scale_factor", scale}}}, {"time_step", {{"value", scale * run_case_spec.time_step.value}}}});
    run_case_spec = resolve_case(experiment.model_reference, overrides, spec.base_dir);
  }
  CaseRunOptions run;
  run.threads = std::max(1, options.base.threads_per_job);
  run.progress = progress;
  identify::CurveSet curves;
  for (auto& [name, curve] : run_case(run_case_spec, published_parameters(), run).curves)
    curves[experiment.name + "/" + name] = curve;
  return curves;
}

}  // namespace

AnchorResult run_anchor(const identify::StudySpec& spec, const GranudrumOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<double> scales = options.resolution_scales;
  scales.push_back(1.0);  // the anchor itself last: the cheap coarse runs report first
  struct Job {
    std::size_t experiment;
    double scale;
    identify::CurveSet curves;
    double seconds = 0.0;
  };
  std::vector<std::vector<Job>> jobs(spec.experiments.size());
  for (std::size_t e = 0; e < spec.experiments.size(); ++e)
    for (const double s : scales) jobs[e].push_back({e, s, {}, 0.0});
  std::mutex progress_mutex;  // experiments report from their own threads
  const ProgressCallback progress = options.base.progress
                                        ? ProgressCallback([&](const std::string& stage, double done, double end) {
                                            const std::lock_guard<std::mutex> lock(progress_mutex);
                                            options.base.progress(stage, done, end);
                                          })
                                        : ProgressCallback{};
  auto run_experiment = [&](std::vector<Job>& list) {
    for (Job& job : list) {
      const auto t0 = std::chrono::steady_clock::now();
      job.curves = run_published(spec, spec.experiments[job.experiment], options, job.scale, progress);
      job.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
  };
  // The experiments run side by side (one thread each) when --jobs allows; each run is
  // deterministic at its thread count, so the order does not change any curve.
  if (options.base.jobs >= 2 && jobs.size() >= 2) {
    std::vector<std::future<void>> running;
    for (auto& list : jobs) running.push_back(std::async(std::launch::async, run_experiment, std::ref(list)));
    for (auto& f : running) f.get();
  } else {
    for (auto& list : jobs) run_experiment(list);
  }
  AnchorResult result;
  identify::CurveSet full;
  for (const auto& list : jobs)
    for (const Job& job : list)
      if (job.scale == 1.0) full.insert(job.curves.begin(), job.curves.end());
  result.errors = surface_errors(spec, full);
  for (const auto& list : jobs)
    for (const Job& job : list) {
      const std::string& experiment = spec.experiments[job.experiment].name;
      for (const auto& [name, curve] : job.curves)
        identify::write_curve_csv(options.base.out_dir / ("published_" + experiment + "_s" + scale_label(job.scale) +
                                                          "_" + name.substr(name.find('/') + 1) + ".csv"),
                                  curve);
      result.runs.push_back({experiment, job.scale, job.seconds, options.base.threads_per_job});
      if (job.scale == 1.0) continue;
      for (const auto& target : spec.targets) {
        if (!target.image || experiment_of(target) != experiment) continue;
        const double radius = (1.0 - target.image->margin) * 0.5 * target.image->diameter;
        const auto coarse = profile_of(curve_for(job.curves, target), radius);
        const auto reference = profile_of(curve_for(full, target), radius);
        const auto photo = profile_of(target.data, radius);
        result.resolution.push_back({target.name, job.scale, 1e3 * imaging::profile_rms_distance(coarse, reference),
                                     1e6 * imaging::profile_differing_area(coarse, reference),
                                     1e3 * imaging::profile_rms_distance(coarse, photo),
                                     1e6 * imaging::profile_differing_area(coarse, photo)});
      }
    }
  result.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

std::string reproduce_granudrum(const GranudrumOptions& options) {
  const ReproduceOptions& o = options.base;
  const fs::path study_file = !options.study_file.empty() ? options.study_file
                                                          : o.cases_dir / (o.quick ? "granudrum_calibration_quick.json"
                                                                                   : "granudrum_calibration.json");
  const identify::StudySpec spec = identify::load_study_file(study_file);
  const auto model = make_study_model(spec);
  const auto cheap_model = make_cheap_level_model(spec, o.out_dir / "study");  // a study with a cheap level
  identify::RunOptions run = detail::study_run_options(o, o.out_dir / "study");
  run.cheap_model = cheap_model.get();
  const identify::StudyResult result = identify::run_study(spec, *model, run);
  const auto calibrated = surface_errors(spec, result.best_curves);
  const auto pictures = write_surface_pictures(spec, result.best_curves, o.out_dir);
  const AnchorResult anchor = options.anchor ? run_anchor(spec, options) : AnchorResult{};
  const std::string text = granudrum_report(spec, result, calibrated, anchor, pictures);
  identify::write_file_atomically(o.out_dir / "granudrum.md", text);
  identify::HtmlReport html("demfit reproduce granudrum", o.out_dir);  // the same text, pictures embedded
  html.markdown(text, true);
  identify::write_html_report(o.out_dir, "granudrum.html", html);
  return text;
}

}  // namespace demfit::cases
