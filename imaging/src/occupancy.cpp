// Occupancy image of projected particles (occupancy.hpp): pixel centres inside any disc count as
// covered in that snapshot; the image is the covered fraction over all snapshots.
#include "demfit/imaging/occupancy.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace demfit::imaging {

OccupancyAccumulator::OccupancyAccumulator(const DrumFrame& frame, int pixels) : frame_(frame), pixels_(pixels) {
  check_drum_diameter(frame.diameter, "occupancy image");
  if (pixels < 32)
    throw std::runtime_error("occupancy image: " + std::to_string(pixels) + " pixels across; give at least 32");
  covered_count_.assign(static_cast<std::size_t>(pixels) * pixels, 0);
  stamp_.assign(covered_count_.size(), 0);
}

void OccupancyAccumulator::add_snapshot(const std::vector<double>& x, const std::vector<double>& z,
                                        const std::vector<double>& radius) {
  if (x.size() != z.size() || x.size() != radius.size())
    throw std::runtime_error("occupancy snapshot: x, z and radius have different lengths (" + std::to_string(x.size()) +
                             ", " + std::to_string(z.size()) + ", " + std::to_string(radius.size()) +
                             "); give one entry per particle");
  for (std::size_t p = 0; p < x.size(); ++p)
    if (!std::isfinite(x[p]) || !std::isfinite(z[p]) || !std::isfinite(radius[p]) || radius[p] < 0.0)
      throw std::runtime_error("occupancy snapshot: particle " + std::to_string(p) +
                               " has a non-finite position or a negative radius; check the simulation output");
  const int n = pixels_;
  const double h = frame_.diameter / (n - 1), half = 0.5 * frame_.diameter;
  std::fill(stamp_.begin(), stamp_.end(), 0);
  for (std::size_t p = 0; p < x.size(); ++p) {
    // Pixel-index box of the disc, then the exact centre-in-disc test.
    const int c0 = std::max(0, static_cast<int>(std::ceil((x[p] - radius[p] + half) / h)));
    const int c1 = std::min(n - 1, static_cast<int>(std::floor((x[p] + radius[p] + half) / h)));
    const int r0 = std::max(0, static_cast<int>(std::ceil((half - z[p] - radius[p]) / h)));
    const int r1 = std::min(n - 1, static_cast<int>(std::floor((half - z[p] + radius[p]) / h)));
    const double r2 = radius[p] * radius[p];
    for (int row = r0; row <= r1; ++row) {
      const double dz = pixel_z(row, n, frame_.diameter) - z[p];
      for (int column = c0; column <= c1; ++column) {
        const double dx = pixel_x(column, n, frame_.diameter) - x[p];
        if (dx * dx + dz * dz <= r2) stamp_[static_cast<std::size_t>(row) * n + column] = 1;
      }
    }
  }
  for (std::size_t k = 0; k < stamp_.size(); ++k) covered_count_[k] += stamp_[k];
  ++snapshots_;
}

GreyImage OccupancyAccumulator::occupancy() const {
  if (snapshots_ == 0)
    throw std::runtime_error("occupancy image: no snapshot was added; add at least one before reading it");
  GreyImage image;
  image.width = image.height = pixels_;
  image.source = "occupancy image";
  image.value.resize(covered_count_.size());
  for (std::size_t k = 0; k < covered_count_.size(); ++k)
    image.value[k] = static_cast<float>(static_cast<double>(covered_count_[k]) / snapshots_);
  return image;
}

}  // namespace demfit::imaging
