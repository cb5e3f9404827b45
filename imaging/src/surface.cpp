// Free-surface extraction (rule in surface.hpp): threshold, bed = material connected to the bottom
// of the compared circle, top of the bed per pixel column with sub-pixel interpolation, then
// `points` equally spaced abscissae across the usable chord.
#include "demfit/imaging/surface.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace demfit::imaging {
namespace {

// The image's pixel grid in the drum frame and the compared circle.
struct Grid {
  int n = 0;                // pixels across (square image)
  double diameter = 0.0;    // [m]
  double h = 0.0;           // [m] pixel pitch D / (N - 1)
  double radius = 0.0;      // [m] R
  double compared = 0.0;    // [m] (1 - margin) R
  std::vector<int> top;     // per column: first row inside the circle (-1: none)
  std::vector<int> bottom;  // per column: last row inside the circle
};

std::string image_name(const GreyImage& image) {
  return image.source.empty() ? std::string("image") : "image '" + image.source + "'";
}

void check_inputs(const GreyImage& image, const DrumFrame& frame, const ProfileOptions& options) {
  const std::string name = image_name(image);
  if (image.width != image.height)
    throw std::runtime_error(
        name + " is " + std::to_string(image.width) + " x " + std::to_string(image.height) +
        " pixels; a drum image must be square and span the drum diameter in both directions: crop it to the drum");
  if (image.width < 32)
    throw std::runtime_error(name + " is " + std::to_string(image.width) +
                             " pixels wide; at least 32 are needed to find a surface");
  if (image.value.size() != static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height))
    throw std::runtime_error(name + ": pixel buffer size is not width x height");
  check_drum_diameter(frame.diameter, name);
  if (!(options.margin >= 0.0 && options.margin < 1.0))
    throw std::runtime_error("margin is " + std::to_string(options.margin) +
                             "; give a fraction of the radius in [0, 1), e.g. 0.1");
  if (options.threshold > 1.0 || std::isnan(options.threshold))
    throw std::runtime_error("threshold is " + std::to_string(options.threshold) +
                             "; give a grey level in [0, 1] or a negative value for Otsu's");
  if (options.points < 2)
    throw std::runtime_error("points is " + std::to_string(options.points) + "; give at least 2 profile abscissae");
}

Grid make_grid(int n, const DrumFrame& frame, double margin) {
  Grid grid;
  grid.n = n;
  grid.diameter = frame.diameter;
  grid.h = frame.diameter / (n - 1);
  grid.radius = 0.5 * frame.diameter;
  grid.compared = (1.0 - margin) * grid.radius;
  grid.top.assign(n, -1);
  grid.bottom.assign(n, -1);
  for (int column = 0; column < n; ++column)
    for (int row = 0; row < n; ++row) {
      const double x = pixel_x(column, n, frame.diameter), z = pixel_z(row, n, frame.diameter);
      if (x * x + z * z > grid.compared * grid.compared) continue;
      if (grid.top[column] < 0) grid.top[column] = row;
      grid.bottom[column] = row;
    }
  return grid;
}

bool inside(const Grid& grid, int column, int row) {
  return column >= 0 && column < grid.n && grid.top[column] >= 0 && row >= grid.top[column] &&
         row <= grid.bottom[column];
}

// Bed mask: material pixels inside the circle 4-connected to a seed, the lowest circle pixel of a
// column below the axis (the drum bottom). Depth-first fill with an explicit stack.
std::vector<unsigned char> bed_mask(const GreyImage& image, const Grid& grid, double threshold, bool dark,
                                    int& material_count) {
  const int n = grid.n;
  std::vector<unsigned char> material(static_cast<std::size_t>(n) * n, 0), bed(material.size(), 0);
  material_count = 0;
  for (int column = 0; column < n; ++column)
    for (int row = grid.top[column]; row >= 0 && row <= grid.bottom[column]; ++row) {
      const float v = image.value[static_cast<std::size_t>(row) * n + column];
      const bool is_material = dark ? v < threshold : v > threshold;
      material[static_cast<std::size_t>(row) * n + column] = is_material;
      material_count += is_material;
    }
  std::vector<int> stack;
  for (int column = 0; column < n; ++column) {
    const int row = grid.bottom[column];
    if (row < 0 || pixel_z(row, n, grid.diameter) >= 0.0) continue;
    const std::size_t k = static_cast<std::size_t>(row) * n + column;
    if (material[k] && !bed[k]) {
      bed[k] = 1;
      stack.push_back(static_cast<int>(k));
    }
  }
  while (!stack.empty()) {
    const int k = stack.back();
    stack.pop_back();
    const int row = k / n, column = k % n;
    const int neighbours[4][2] = {{column - 1, row}, {column + 1, row}, {column, row - 1}, {column, row + 1}};
    for (const auto& [c, r] : neighbours) {
      if (!inside(grid, c, r)) continue;
      const std::size_t m = static_cast<std::size_t>(r) * n + c;
      if (material[m] && !bed[m]) {
        bed[m] = 1;
        stack.push_back(static_cast<int>(m));
      }
    }
  }
  return bed;
}

// Median grey levels of the material and of the empty pixels inside the circle.
void class_levels(const GreyImage& image, const Grid& grid, double threshold, bool dark, SurfaceProfile& profile) {
  std::vector<float> material, empty;
  for (int column = 0; column < grid.n; ++column)
    for (int row = grid.top[column]; row >= 0 && row <= grid.bottom[column]; ++row) {
      const float v = image.value[static_cast<std::size_t>(row) * grid.n + column];
      ((dark ? v < threshold : v > threshold) ? material : empty).push_back(v);
    }
  for (auto [values, level] :
       {std::pair{&material, &profile.material_level}, std::pair{&empty, &profile.empty_level}}) {
    if (values->empty()) continue;
    const auto middle = values->begin() + static_cast<std::ptrdiff_t>(values->size() / 2);
    std::nth_element(values->begin(), middle, values->end());
    *level = *middle;
  }
}

// Per column: height [m] of the top of the bed, or NaN when the column has no bed pixel or the bed
// reaches the top of the circle. Sub-pixel: the grey level is interpolated linearly between the
// topmost bed pixel and the empty pixel above it, and the surface put where it crosses the threshold.
std::vector<double> column_heights(const GreyImage& image, const Grid& grid, const std::vector<unsigned char>& bed,
                                   double threshold) {
  const int n = grid.n;
  std::vector<double> height(n, std::nan(""));
  for (int column = 0; column < n; ++column) {
    int row = grid.top[column];
    if (row < 0) continue;
    while (row <= grid.bottom[column] && !bed[static_cast<std::size_t>(row) * n + column]) ++row;
    if (row > grid.bottom[column] || row == grid.top[column]) continue;
    const double below = image.value[static_cast<std::size_t>(row) * n + column];
    const double above = image.value[static_cast<std::size_t>(row - 1) * n + column];
    double fraction = 0.5;
    if (above != below) fraction = std::min(1.0, std::max(0.0, (threshold - below) / (above - below)));
    height[column] = pixel_z(row, n, grid.diameter) + fraction * grid.h;
  }
  return height;
}

// The bed-shape fractions of rule 5 (surface.hpp).
void measure_bed_shape(const Grid& grid, const std::vector<unsigned char>& bed, int material_count,
                       const std::vector<double>& height, SurfaceProfile& profile) {
  const int n = grid.n;
  long bed_count = 0, below = 0, bed_below = 0;
  int first = -1, last = -1, covered = 0;
  for (int column = 0; column < n; ++column) {
    for (int row = grid.top[column]; row >= 0 && row <= grid.bottom[column]; ++row) {
      const bool is_bed = bed[static_cast<std::size_t>(row) * n + column];
      bed_count += is_bed;
      if (!std::isnan(height[column]) && pixel_z(row, n, grid.diameter) < height[column]) {
        ++below;
        bed_below += is_bed;
      }
    }
    if (std::isnan(height[column])) continue;
    if (first < 0) first = column;
    last = column;
    ++covered;
  }
  profile.bed_share = material_count > 0 ? static_cast<double>(bed_count) / material_count : 0.0;
  profile.bed_solidity = below > 0 ? static_cast<double>(bed_below) / below : 0.0;
  profile.surface_cover = first >= 0 ? static_cast<double>(covered) / (last - first + 1) : 0.0;
}

void check_bed_shape(const GreyImage& image, const SurfaceProfile& profile) {
  auto refuse = [&](const std::string& what, double value, double least) {
    std::ostringstream text;
    text.precision(3);
    text << image_name(image) << " does not look like a drum photo: " << what << " is " << value << " (at least "
         << least << " for one powder bed resting on the drum bottom under one free surface, threshold "
         << profile.threshold_used << "); check that it is a drum photo cropped to the drum, the contrast "
         << "(--inverted) and the threshold";
    throw std::runtime_error(text.str());
  };
  if (profile.bed_share < kMinBedShare)
    refuse("the share of the material pixels connected to the drum bottom", profile.bed_share, kMinBedShare);
  if (profile.bed_solidity < kMinBedSolidity)
    refuse("the share of the pixels below the surface that are bed", profile.bed_solidity, kMinBedSolidity);
  if (profile.surface_cover < kMinSurfaceCover)
    refuse("the share of the columns across the chord with a surface", profile.surface_cover, kMinSurfaceCover);
}

// `points` abscissae from the first to the last column with a surface; z interpolated linearly
// between neighbouring columns; abscissae next to a column without surface are dropped.
void sample_profile(const Grid& grid, const std::vector<double>& height, int points, SurfaceProfile& profile) {
  int first = -1, last = -1;
  for (int column = 0; column < grid.n; ++column)
    if (!std::isnan(height[column])) {
      if (first < 0) first = column;
      last = column;
    }
  if (first < 0 || last == first) return;
  const double x0 = pixel_x(first, grid.n, grid.diameter), x1 = pixel_x(last, grid.n, grid.diameter);
  for (int k = 0; k < points; ++k) {
    const double x = k + 1 == points ? x1 : x0 + (x1 - x0) * k / (points - 1);
    const double u = (x + grid.radius) / grid.h;
    const int left = std::min(last - 1, std::max(first, static_cast<int>(std::floor(u))));
    const double w = std::min(1.0, std::max(0.0, u - left));
    const double zl = height[left], zr = height[left + 1];
    if ((w < 1.0 && std::isnan(zl)) || (w > 0.0 && std::isnan(zr))) continue;
    const double z = w == 0.0 ? zl : w == 1.0 ? zr : (1.0 - w) * zl + w * zr;
    profile.x.push_back(x);
    profile.z.push_back(z);
  }
}

}  // namespace

void check_drum_diameter(double diameter, const std::string& what) {
  if (diameter >= kMinDrumDiameter && diameter <= kMaxDrumDiameter) return;
  std::ostringstream text;
  text << what << ": drum diameter " << diameter << " m is outside " << kMinDrumDiameter * 1e3 << " mm .. "
       << kMaxDrumDiameter << " m; give the inner drum diameter in metres, e.g. 0.084 m for 84 mm";
  throw std::runtime_error(text.str());
}

double pixel_x(int column, int n, double diameter) { return -0.5 * diameter + column * diameter / (n - 1); }
double pixel_z(int row, int n, double diameter) { return 0.5 * diameter - row * diameter / (n - 1); }

ProfileOptions occupancy_profile_options(const ProfileOptions& photo_options) {
  ProfileOptions options = photo_options;
  options.threshold = 0.5;
  options.material_is_dark = false;
  options.require_single_bed = false;
  return options;
}

double equivalent_occupancy(const SurfaceProfile& profile) {
  if (profile.material_level == profile.empty_level)
    throw std::runtime_error(
        "equivalent occupancy: the profile's material and empty grey levels are equal; extract a surface first");
  return (profile.threshold_used - profile.empty_level) / (profile.material_level - profile.empty_level);
}

SurfaceProfile extract_surface(const GreyImage& image, const DrumFrame& frame, const ProfileOptions& options) {
  check_inputs(image, frame, options);
  const Grid grid = make_grid(image.width, frame, options.margin);
  SurfaceProfile profile;
  profile.threshold_used = options.threshold >= 0.0 ? options.threshold : otsu_threshold(image, options.margin);
  profile.compared_radius = grid.compared;
  profile.pixel_size = grid.h;
  int material_count = 0;
  const std::vector<unsigned char> bed =
      bed_mask(image, grid, profile.threshold_used, options.material_is_dark, material_count);
  class_levels(image, grid, profile.threshold_used, options.material_is_dark, profile);
  const std::vector<double> height = column_heights(image, grid, bed, profile.threshold_used);
  sample_profile(grid, height, options.points, profile);
  measure_bed_shape(grid, bed, material_count, height, profile);
  if (profile.x.size() < 2) {
    const std::string what =
        material_count == 0 ? "no pixel is material" : "the material fills the circle or does not reach its bottom";
    throw std::runtime_error(
        image_name(image) + ": no free surface found inside the compared circle (" + what + " at threshold " +
        std::to_string(profile.threshold_used) + ", material " + (options.material_is_dark ? "dark" : "light") +
        "); check that it is a drum photo, the threshold, the contrast (--inverted) and the margin");
  }
  if (options.require_single_bed) check_bed_shape(image, profile);
  return profile;
}

}  // namespace demfit::imaging
