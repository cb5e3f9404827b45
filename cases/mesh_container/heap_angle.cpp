// Heap angle of repose from particle positions (see mesh_container_case.hpp, kHeapAngleDefinition).
// A GranuHeap-like pedestal heap is a cone h(r) = H - r tan(theta) above the pedestal; its
// surface in an annulus is the highest particle top there, so a straight line through those
// heights against radius has slope -tan(theta). The highest top of an annulus sits near its
// inner edge on every annulus alike: that offset shifts the line, not its slope.
#include <cmath>
#include <limits>
#include <numbers>

#include "mesh_container_case.hpp"

namespace demfit::cases::detail {

double heap_angle_degrees(const std::vector<std::array<double, 3>>& positions, const std::vector<double>& radii,
                          const HeapAngleSpec& heap) {
  const auto bins = static_cast<std::size_t>(heap.bins);
  const double width = (heap.r_max - heap.r_min) / static_cast<double>(bins);
  std::vector<double> top(bins, -std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const auto& p = positions[i];
    if (p[2] < heap.base_z) continue;
    const double r = std::hypot(p[0] - heap.center[0], p[1] - heap.center[1]);
    if (r < heap.r_min || r >= heap.r_max) continue;
    const auto k = std::min(bins - 1, static_cast<std::size_t>((r - heap.r_min) / width));
    top[k] = std::max(top[k], p[2] + radii[i]);
  }
  // Least squares h = a + s r over the occupied annuli (mid-radii).
  double n = 0.0, sr = 0.0, sh = 0.0, srr = 0.0, srh = 0.0;
  for (std::size_t k = 0; k < bins; ++k) {
    if (!std::isfinite(top[k])) continue;
    const double r = heap.r_min + (static_cast<double>(k) + 0.5) * width;
    n += 1.0;
    sr += r;
    sh += top[k];
    srr += r * r;
    srh += r * top[k];
  }
  if (n < 2.0) return std::numeric_limits<double>::quiet_NaN();
  const double slope = (n * srh - sr * sh) / (n * srr - sr * sr);
  return std::atan(-slope) * 180.0 / std::numbers::pi;
}

}  // namespace demfit::cases::detail
