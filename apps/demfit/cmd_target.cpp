// demfit target from-image PHOTO --diameter 84mm --out DIR: the free-surface profile of a drum
// photo in the drum frame (free_surface.csv, mm) and an overlay picture (overlay.png). The
// extraction rule is in imaging/include/demfit/imaging/surface.hpp.
// demfit target compare SIMULATED.csv MEASURED.csv: how far two such profiles lie apart, and the
// gap split into level, tilt and shape (imaging::profile_gap_parts); writes nothing.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>

#include "cli_safety.hpp"
#include "commands.hpp"
#include "demfit/identify/curve_io.hpp"
#include "demfit/identify/safe_output.hpp"
#include "demfit/imaging/imaging.hpp"

namespace demfit::apps {
namespace {

namespace fs = std::filesystem;

struct TargetFromImageOptions {
  std::string photo;
  std::string diameter;
  double threshold = -1.0;
  bool inverted = false;
  double margin = 0.1;
  int points = 41;
  std::string out;
};

// Documented ranges: a lab drum's inner diameter [m]; profile abscissae (each costs a column scan
// of the photo); profile coordinates of target compare [mm] (a drum is never a kilometre wide).
constexpr double kMinDiameter = 1e-3, kMaxDiameter = 10.0;
constexpr int kMaxProfilePoints = 100000;
constexpr double kMaxProfileMm = 1e6;

// "84mm", "84 mm", "0.084m" or a bare number (metres) -> metres, within [kMinDiameter, kMaxDiameter].
double parse_diameter(const std::string& text) {
  static const std::regex pattern(R"(\s*([0-9]*\.?[0-9]+(?:[eE][-+]?[0-9]+)?)\s*(mm|m)?\s*)");
  std::smatch match;
  if (!std::regex_match(text, match, pattern))
    throw std::runtime_error("--diameter " + identify::quote_path(text) +
                             ": give a number with unit mm or m, e.g. 84mm or 0.084m (a bare number is metres)");
  const double value = parse_number(match[1].str(), "--diameter") * (match[2].str() == "mm" ? 1e-3 : 1.0);
  if (!(value >= kMinDiameter))
    throw std::runtime_error("--diameter " + identify::quote_path(text) +
                             ": the drum diameter must be at least 1 mm (range 1 mm to 10 m), e.g. 84mm");
  if (value > kMaxDiameter)
    throw std::runtime_error("--diameter " + identify::quote_path(text) + " is " + std::to_string(value) +
                             " m, larger than any lab drum (range 1 mm to 10 m); a bare number is metres: add the "
                             "unit, e.g. 84mm");
  return value;
}

std::string format_csv(const imaging::SurfaceProfile& profile, const imaging::DrumFrame& frame,
                       const TargetFromImageOptions& o) {
  std::ostringstream csv;
  csv.precision(6);
  csv << "# free surface of the bed in the drum frame: x right as seen in the picture, z up, origin on the drum axis, "
         "mm; "
      << "the square image spans the inner diameter " << frame.diameter * 1e3 << " mm\n"
      << "# source: " << identify::printable(o.photo) << "; threshold " << profile.threshold_used
      << (o.threshold < 0.0 ? " (Otsu)" : " (given)") << "; material " << (o.inverted ? "light" : "dark") << "; margin "
      << o.margin << " (compared circle radius " << profile.compared_radius * 1e3 << " mm); pixel "
      << profile.pixel_size * 1e3 << " mm\n"
      << "x_mm,z_mm\n";
  for (std::size_t i = 0; i < profile.x.size(); ++i) csv << profile.x[i] * 1e3 << ',' << profile.z[i] * 1e3 << '\n';
  return csv.str();
}

void run_target_from_image(const TargetFromImageOptions& o) {
  // Everything is computed before anything is written (bad input leaves nothing behind).
  const imaging::DrumFrame frame{parse_diameter(o.diameter)};
  if (o.threshold > 1.0)
    throw std::runtime_error("--threshold " + std::to_string(o.threshold) +
                             ": give a grey level in [0, 1] (0 black, 1 white)");
  if (!(o.margin >= 0.0 && o.margin < 1.0))
    throw std::runtime_error("--margin " + std::to_string(o.margin) +
                             ": give a fraction of the radius in [0, 1), e.g. 0.1");
  if (o.points < 2) throw std::runtime_error("--points " + std::to_string(o.points) + ": give at least 2");
  require_at_most(o.points, kMaxProfilePoints, "--points", "a profile needs a few dozen points (default 41)");
  const identify::OutputRequest request{identify::OutputKind::target, {o.photo}};
  identify::check_output_folder(o.out, request);  // before the photo is read
  imaging::ProfileOptions options;
  options.threshold = o.threshold;
  options.material_is_dark = !o.inverted;
  options.margin = o.margin;
  options.points = o.points;
  const imaging::GreyImage photo = imaging::read_grey_image(o.photo);
  const imaging::SurfaceProfile profile = imaging::extract_surface(photo, frame, options);
  const imaging::SurfaceLine line = imaging::fit_surface_line(profile);
  const std::string csv = format_csv(profile, frame, o);
  const std::string png = imaging::encode_png(imaging::draw_overlay(photo, frame, profile));
  // The output-folder rules and the one atomic writer of every command.
  identify::prepare_output_folder(o.out, request);
  identify::write_file_atomically(fs::path(o.out) / "free_surface.csv", csv);
  identify::write_file_atomically(fs::path(o.out) / "overlay.png", png);
  std::printf(
      "demfit target from-image: %s -> %s\n  %zu points, x %.2f .. %.2f mm, threshold %.3f%s\n"
      "  straight-line fit over the whole profile: angle %.2f deg (negative = bed lifted on the left), residual %.3f "
      "mm RMS\n",
      identify::printable(o.photo).c_str(), identify::printable(o.out).c_str(), profile.x.size(),
      profile.x.front() * 1e3, profile.x.back() * 1e3, profile.threshold_used, o.threshold < 0.0 ? " (Otsu)" : "",
      line.angle_deg, line.residual_rms * 1e3);
}

struct TargetCompareOptions {
  std::string simulated, measured;
};

// A profile CSV (x_mm, z_mm) in metres; x must increase (both of demfit's profile writers sort it).
// Coordinates beyond kMaxProfileMm are refused: their squares overflow the gap's sums.
imaging::SurfaceProfile read_profile(const std::string& file) {
  const identify::Curve curve = identify::read_curve_csv(file, "x_mm", "z_mm");
  for (std::size_t i = 0; i < curve.x.size(); ++i)
    if (!(std::abs(curve.x[i]) <= kMaxProfileMm && std::abs(curve.y[i]) <= kMaxProfileMm))
      throw std::runtime_error("profile " + identify::quote_path(file) + " point " + std::to_string(i + 1) +
                               ": a coordinate beyond the limit of 1e6 mm; give x_mm and z_mm in millimetres");
  return imaging::profile_from_mm(curve.x, curve.y, file);
}

void run_target_compare(const TargetCompareOptions& o) {
  const imaging::SurfaceProfile simulated = read_profile(o.simulated), measured = read_profile(o.measured);
  const imaging::ProfileGapParts parts = imaging::profile_gap_parts(simulated, measured);
  const double area = imaging::profile_differing_area(simulated, measured);
  for (double v : {parts.rms, parts.level_offset, parts.angle_difference_deg, parts.tilt_rms, parts.shape_rms, area})
    if (!std::isfinite(v))
      throw std::runtime_error("target compare: the gap of " + identify::quote_path(o.simulated) + " and " +
                               identify::quote_path(o.measured) +
                               " is not a finite number; check that both profiles are in millimetres");
  const double lo = std::max(simulated.x.front(), measured.x.front());
  const double hi = std::min(simulated.x.back(), measured.x.back());
  std::printf(
      "demfit target compare: %s against %s (common x-range %.2f .. %.2f mm)\n"
      "  RMS gap %.3f mm, differing area %.1f mm2\n"
      "  split: level offset %+.3f mm (> 0: simulated above measured), angle difference %+.2f deg, tilt %.3f mm "
      "RMS, shape %.3f mm RMS\n",
      identify::printable(o.simulated).c_str(), identify::printable(o.measured).c_str(), lo * 1e3, hi * 1e3,
      parts.rms * 1e3, area * 1e6, parts.level_offset * 1e3, parts.angle_difference_deg, parts.tilt_rms * 1e3,
      parts.shape_rms * 1e3);
}

void register_compare(CLI::App& target) {
  auto options = std::make_shared<TargetCompareOptions>();
  auto* cmd = target.add_subcommand(
      "compare",
      "Compare two free-surface profiles (CSV with columns x_mm,z_mm in the drum frame, e.g. a simulated\n"
      "free_surface_image.csv and a photo's free_surface.csv) over their common x-range. Prints the RMS gap\n"
      "(mm), the differing area (mm2), and the gap split into three orthogonal parts: the level offset\n"
      "(mean gap, mm), the tilt (angle difference in degrees and its RMS in mm) and the shape left over\n"
      "(RMS, mm); RMS^2 = level^2 + tilt^2 + shape^2. Coordinates beyond 1e6 mm are refused. Writes no file.");
  cmd->add_option("simulated", options->simulated, "profile CSV (x_mm,z_mm) whose gap is reported (e.g. simulated)")
      ->required();
  cmd->add_option("measured", options->measured, "reference profile CSV (x_mm,z_mm), e.g. from target from-image")
      ->required();
  cmd->callback([options] { run_target_compare(*options); });
}

}  // namespace

void register_target(CLI::App& app) {
  auto* target = app.add_subcommand("target", "Make study targets from measurements (e.g. a drum photo)");
  target->require_subcommand(1);
  auto options = std::make_shared<TargetFromImageOptions>();
  auto* cmd = target->add_subcommand(
      "from-image",
      "Extract the free-surface profile of a rotating-drum photo (BMP, PNG or JPEG).\n"
      "The square image must span the drum's inner diameter in both directions, centred on the axis.\n"
      "Writes into --out: free_surface.csv (x_mm,z_mm: drum frame, x right as seen in the picture,\n"
      "z up, origin on the drum axis, millimetres; '#' lines state the threshold and source) and\n"
      "overlay.png (the photo, the profile in red, the compared circle in blue). --out must be new, empty\n"
      "or a folder demfit made (never the working folder); nothing is written when the input is bad.");
  cmd->add_option("photo", options->photo, "drum photo (BMP, PNG or JPEG)")->required();
  cmd->add_option("--diameter", options->diameter,
                  "inner drum diameter spanned by the image, with unit mm or m (e.g. 84mm or 0.084m; a bare number is "
                  "metres), from 1 mm to 10 m")
      ->required();
  cmd->add_option("--threshold", options->threshold,
                  "grey level in [0,1] separating material from empty (0 black, 1 white); default: automatic (Otsu)");
  cmd->add_flag("--inverted", options->inverted, "material is light on a dark background (default: powder dark)");
  cmd->add_option("--margin", options->margin,
                  "ignore pixels beyond (1 - margin) x radius from the axis (the drawn outline), fraction of the "
                  "radius (default 0.1)");
  cmd->add_option("--points", options->points,
                  "profile abscissae, equally spaced across the surface's chord (default 41, at most 100000)");
  cmd->add_option("--out", options->out, "output folder (created if missing)")->required()->check(non_empty_path());
  cmd->callback([options] { run_target_from_image(*options); });
  register_compare(*target);
}

}  // namespace demfit::apps
