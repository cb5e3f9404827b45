// Dynamic angle of a drum bed by named definitions (see bed_angles.hpp).
#include "demfit/cases/bed_angles.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <stdexcept>

#include "demfit/cases/free_surface.hpp"

namespace demfit::cases {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kNeighbourTolerance = 0.1;  // as the cluster surface: gap < 10 % of r_i + r_j

double mean_radius(const std::vector<double>& radii) {
  double sum = 0.0;
  for (double r : radii) sum += r;
  return sum / static_cast<double>(radii.size());
}

void check_bed(const std::vector<std::array<double, 3>>& positions, const std::vector<double>& radii) {
  if (positions.size() != radii.size()) throw std::runtime_error("bed angle: radii/positions size mismatch");
}

// Separable Gaussian smoothing of a row-major nx * ny field, sigma in cells, zero outside.
std::vector<double> smooth(const std::vector<double>& field, int nx, int ny, double sigma_cells) {
  const int half = static_cast<int>(std::ceil(3.0 * sigma_cells));
  std::vector<double> kernel(2 * half + 1);
  double total = 0.0;
  for (int k = -half; k <= half; ++k) total += kernel[k + half] = std::exp(-0.5 * k * k / (sigma_cells * sigma_cells));
  for (double& w : kernel) w /= total;
  std::vector<double> along_x(field.size(), 0.0), both(field.size(), 0.0);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      for (int k = -half; k <= half; ++k)
        if (i + k >= 0 && i + k < nx) along_x[j * nx + i] += kernel[k + half] * field[j * nx + i + k];
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      for (int k = -half; k <= half; ++k)
        if (j + k >= 0 && j + k < ny) both[j * nx + i] += kernel[k + half] * along_x[(j + k) * nx + i];
  return both;
}

}  // namespace

double line_fit_angle_degrees(const std::vector<double>& x, const std::vector<double>& y) {
  const std::size_t n = std::min(x.size(), y.size());
  if (n < 2) return kNaN;
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t k = 0; k < n; ++k) {
    sx += x[k];
    sy += y[k];
    sxx += x[k] * x[k];
    sxy += x[k] * y[k];
  }
  const double count = static_cast<double>(n);
  const double denominator = count * sxx - sx * sx;
  if (!(denominator > 0.0)) return kNaN;
  return std::atan(std::fabs((count * sxy - sx * sy) / denominator)) * 180.0 / std::numbers::pi;
}

double slab_surface_angle_degrees(const std::vector<std::array<double, 3>>& positions,
                                  const std::vector<double>& radii, double drum_length) {
  check_bed(positions, radii);
  if (positions.empty()) return kNaN;
  const double r_mean = mean_radius(radii);
  std::vector<int> neighbours(positions.size(), 0);
  for_each_close_pair(positions, radii, kNeighbourTolerance, [&](int i, int j) {
    ++neighbours[i];
    ++neighbours[j];
  });
  const double bin = 4.0 * r_mean;
  std::map<long long, double> top_of_bin;  // ordered by x: the chord is read off its ends
  for (std::size_t i = 0; i < positions.size(); ++i) {
    if (neighbours[i] < 3 || std::fabs(positions[i][2] - 0.5 * drum_length) > 2.0 * r_mean) continue;
    const auto b = static_cast<long long>(std::floor(positions[i][0] / bin));
    const double top = positions[i][1] + radii[i];
    auto [it, inserted] = top_of_bin.emplace(b, top);
    if (!inserted) it->second = std::max(it->second, top);
  }
  if (top_of_bin.size() < 2) return kNaN;
  const double first = (static_cast<double>(top_of_bin.begin()->first) + 0.5) * bin;
  const double last = (static_cast<double>(top_of_bin.rbegin()->first) + 0.5) * bin;
  const double margin = 0.2 * (last - first);
  std::vector<double> x, y;
  for (const auto& [b, top] : top_of_bin) {
    const double centre = (static_cast<double>(b) + 0.5) * bin;
    if (centre < first + margin || centre > last - margin) continue;
    x.push_back(centre);
    y.push_back(top);
  }
  return line_fit_angle_degrees(x, y);
}

double instrument_angle_degrees(const std::vector<std::array<double, 3>>& positions, const std::vector<double>& radii,
                                double drum_diameter, double drum_length) {
  check_bed(positions, radii);
  if (positions.empty() || !(drum_diameter > 0.0) || !(drum_length > 0.0)) return kNaN;
  const double r_mean = mean_radius(radii);
  // Half a mean radius per cell, but at most kMaxCells a side: the field and its two smoothing
  // passes hold 3 n^2 doubles (~100 MB at 2048), so a drum thousands of radii across is sampled
  // more coarsely instead of exhausting memory.
  constexpr int kMaxCells = 2048;
  const double half = 0.5 * drum_diameter;
  const double cell = std::max(0.5 * r_mean, drum_diameter / (kMaxCells - 1));
  const int n = static_cast<int>(std::ceil(drum_diameter / cell)) + 1;
  std::vector<double> phi(static_cast<std::size_t>(n) * n, 0.0);
  const auto centre_of = [&](int k) { return -half + (k + 0.5) * cell; };
  for (std::size_t p = 0; p < positions.size(); ++p) {
    const double r = radii[p];
    const int i_lo = std::max(0, static_cast<int>(std::floor((positions[p][0] - r + half) / cell)));
    const int i_hi = std::min(n - 1, static_cast<int>(std::floor((positions[p][0] + r + half) / cell)));
    const int j_lo = std::max(0, static_cast<int>(std::floor((positions[p][1] - r + half) / cell)));
    const int j_hi = std::min(n - 1, static_cast<int>(std::floor((positions[p][1] + r + half) / cell)));
    for (int j = j_lo; j <= j_hi; ++j)
      for (int i = i_lo; i <= i_hi; ++i) {
        const double d2 = std::pow(centre_of(i) - positions[p][0], 2) + std::pow(centre_of(j) - positions[p][1], 2);
        if (d2 < r * r) phi[static_cast<std::size_t>(j) * n + i] += 2.0 * std::sqrt(r * r - d2) / drum_length;
      }
  }
  phi = smooth(phi, n, n, std::max(1.0, r_mean / cell));
  const double threshold = 0.5 * *std::max_element(phi.begin(), phi.end());
  const double circle_radius = 0.1 * drum_diameter;  // the central circle of diameter D/5
  std::vector<double> x, y;
  for (int i = 0; i < n; ++i) {
    for (int j = n - 1; j > 0; --j) {  // from the top down: the first crossing is the interface
      const double above = phi[static_cast<std::size_t>(j) * n + i], below = phi[static_cast<std::size_t>(j - 1) * n + i];
      if (above >= threshold) break;  // the column starts inside the bed: no interface from above
      if (below < threshold) continue;
      const double crossing = centre_of(j) - cell * (threshold - above) / (below - above);
      if (std::hypot(centre_of(i), crossing) <= circle_radius) {
        x.push_back(centre_of(i));
        y.push_back(crossing);
      }
      break;
    }
  }
  return x.size() < 3 ? kNaN : line_fit_angle_degrees(x, y);
}

}  // namespace demfit::cases
