#pragma once
// The simulated side of an image target: particles projected along the drum axis onto the picture
// plane and rasterised as discs into an occupancy image, averaged over snapshots of a time window.
#include <vector>

#include "demfit/imaging/image.hpp"
#include "demfit/imaging/surface.hpp"

namespace demfit::imaging {

// Accumulates snapshots into a square image of `pixels` x `pixels` spanning the drum diameter,
// with the pixel-centre convention of surface.hpp (centres at -R..+R). A pixel is covered in a
// snapshot when its centre lies inside at least one particle's disc (|p - c| <= radius);
// occupancy = fraction of snapshots in which it was covered (0 never .. 1 always).
// Extract its surface with occupancy_profile_options(...) (material = occupancy > 0.5).
class OccupancyAccumulator {
 public:
  // Throws std::runtime_error when the diameter is outside [kMinDrumDiameter, kMaxDrumDiameter]
  // or pixels < 32.
  OccupancyAccumulator(const DrumFrame& frame, int pixels);

  // Positions in the drum frame (x right, z up, metres, origin on the axis) and radii [m] of one
  // snapshot. Throws when the sizes differ or a value is not finite or a radius is negative.
  void add_snapshot(const std::vector<double>& x, const std::vector<double>& z, const std::vector<double>& radius);

  // The occupancy as a grey image (value = covered fraction). Throws when no snapshot was added.
  GreyImage occupancy() const;
  int snapshots() const { return snapshots_; }
  int pixels() const { return pixels_; }

 private:
  DrumFrame frame_;
  int pixels_ = 0;
  int snapshots_ = 0;
  std::vector<int> covered_count_;    // per pixel: snapshots in which it was covered
  std::vector<unsigned char> stamp_;  // per pixel: covered in the current snapshot
};

}  // namespace demfit::imaging
