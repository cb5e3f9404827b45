// Free-surface extraction: largest connected cluster + silhouette envelope (see free_surface.hpp).
#include "demfit/cases/free_surface.hpp"

#include "demfit/cases/bed_angles.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <numeric>
#include <stdexcept>
#include <unordered_map>

namespace demfit::cases {
namespace {

// Union-find with path halving; deterministic (union by index).
int find_root(std::vector<int>& parent, int i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}

void unite(std::vector<int>& parent, int a, int b) {
  a = find_root(parent, a);
  b = find_root(parent, b);
  if (a != b) parent[std::max(a, b)] = std::min(a, b);
}

long long cell_key(long long ix, long long iy, long long iz) {
  // 21 bits per axis with an offset: plenty for a drum a few hundred particles across.
  constexpr long long offset = 1 << 20;
  return ((ix + offset) << 42) | ((iy + offset) << 21) | (iz + offset);
}

}  // namespace

void for_each_close_pair(const std::vector<std::array<double, 3>>& positions, const std::vector<double>& radii,
                         double contact_tolerance, const std::function<void(int, int)>& visit) {
  const int n = static_cast<int>(positions.size());
  if (radii.size() != positions.size()) throw std::runtime_error("free surface: radii/positions size mismatch");
  if (n == 0) return;
  const double r_max = *std::max_element(radii.begin(), radii.end());
  const double cell = 2.0 * r_max * (1.0 + contact_tolerance);
  std::unordered_map<long long, std::vector<int>> grid;
  std::vector<std::array<long long, 3>> cell_of(n);
  for (int i = 0; i < n; ++i) {
    for (int d = 0; d < 3; ++d) cell_of[i][d] = static_cast<long long>(std::floor(positions[i][d] / cell));
    grid[cell_key(cell_of[i][0], cell_of[i][1], cell_of[i][2])].push_back(i);
  }
  for (int i = 0; i < n; ++i) {
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          auto it = grid.find(cell_key(cell_of[i][0] + dx, cell_of[i][1] + dy, cell_of[i][2] + dz));
          if (it == grid.end()) continue;
          for (int j : it->second) {
            if (j <= i) continue;
            double d2 = 0.0;
            for (int d = 0; d < 3; ++d) d2 += std::pow(positions[j][d] - positions[i][d], 2);
            const double reach = (1.0 + contact_tolerance) * (radii[i] + radii[j]);
            if (d2 < reach * reach) visit(i, j);
          }
        }
  }
}

std::vector<int> largest_cluster(const std::vector<std::array<double, 3>>& positions, const std::vector<double>& radii,
                                 double contact_tolerance) {
  const int n = static_cast<int>(positions.size());
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  for_each_close_pair(positions, radii, contact_tolerance, [&](int i, int j) { unite(parent, i, j); });
  if (n == 0) return {};
  std::vector<int> size(n, 0);
  for (int i = 0; i < n; ++i) ++size[find_root(parent, i)];
  // Largest cluster; ties go to the lowest root index, so the result is deterministic.
  const int best_root = static_cast<int>(std::max_element(size.begin(), size.end()) - size.begin());
  std::vector<int> members;
  for (int i = 0; i < n; ++i)
    if (find_root(parent, i) == best_root) members.push_back(i);
  return members;
}

SurfaceProfile extract_free_surface(const std::vector<std::array<double, 3>>& positions,
                                    const std::vector<double>& radii, const SurfaceOptions& options) {
  if (options.points < 2 || !(options.x_max > options.x_min)) {
    throw std::runtime_error("free surface: need points >= 2 and x_max > x_min");
  }
  SurfaceProfile profile;
  const double step = (options.x_max - options.x_min) / (options.points - 1);
  for (int k = 0; k < options.points; ++k) profile.x.push_back(options.x_min + k * step);
  profile.height.assign(options.points, -std::numeric_limits<double>::infinity());
  for (int i : largest_cluster(positions, radii, options.contact_tolerance)) {
    const double xp = positions[i][0];
    const double yp = positions[i][1];
    const double r = radii[i];
    // Only the abscissae under this particle's silhouette.
    const int k_lo = std::max(0, static_cast<int>(std::ceil((xp - r - options.x_min) / step)));
    const int k_hi = std::min(options.points - 1, static_cast<int>(std::floor((xp + r - options.x_min) / step)));
    for (int k = k_lo; k <= k_hi; ++k) {
      const double dx = profile.x[k] - xp;
      const double h2 = r * r - dx * dx;
      if (h2 < 0.0) continue;
      profile.height[k] = std::max(profile.height[k], yp + std::sqrt(h2));
    }
  }
  for (double& h : profile.height)
    if (!std::isfinite(h)) h = std::numeric_limits<double>::quiet_NaN();
  return profile;
}

SurfaceProfile average_profiles(const std::vector<SurfaceProfile>& profiles) {
  if (profiles.empty()) throw std::runtime_error("free surface: no profiles to average");
  SurfaceProfile mean;
  mean.x = profiles.front().x;
  mean.height.assign(mean.x.size(), 0.0);
  std::vector<int> count(mean.x.size(), 0);
  for (const auto& p : profiles) {
    if (p.x != mean.x) throw std::runtime_error("free surface: profiles sampled on different abscissae");
    for (std::size_t k = 0; k < p.x.size(); ++k) {
      if (std::isfinite(p.height[k])) {
        mean.height[k] += p.height[k];
        ++count[k];
      }
    }
  }
  for (std::size_t k = 0; k < mean.x.size(); ++k) {
    const bool kept = 2 * count[k] >= static_cast<int>(profiles.size()) && count[k] > 0;
    mean.height[k] = kept ? mean.height[k] / count[k] : std::numeric_limits<double>::quiet_NaN();
  }
  return mean;
}

double repose_angle_degrees(const SurfaceProfile& profile, double x_low, double x_high) {
  std::vector<double> x, y;
  for (std::size_t k = 0; k < profile.x.size(); ++k) {
    if (profile.x[k] < x_low || profile.x[k] > x_high || !std::isfinite(profile.height[k])) continue;
    x.push_back(profile.x[k]);
    y.push_back(profile.height[k]);
  }
  return line_fit_angle_degrees(x, y);
}

}  // namespace demfit::cases
