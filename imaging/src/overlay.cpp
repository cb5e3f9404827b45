// Overlay picture (overlay.hpp): grey photo, compared circle in blue, profile in red.
#include "demfit/imaging/overlay.hpp"

#include <cmath>

namespace demfit::imaging {
namespace {

void paint(RgbImage& image, int column, int row, std::uint8_t red, std::uint8_t green, std::uint8_t blue) {
  if (column < 0 || row < 0 || column >= image.width || row >= image.height) return;
  const std::size_t k = 3 * (static_cast<std::size_t>(row) * image.width + column);
  image.rgb[k] = red;
  image.rgb[k + 1] = green;
  image.rgb[k + 2] = blue;
}

// Fractional pixel coordinates of a drum-frame point (centres at -R..+R, row 0 at the top).
void to_pixel(const RgbImage& image, const DrumFrame& frame, double x, double z, double& column, double& row) {
  column = (x + 0.5 * frame.diameter) / frame.diameter * (image.width - 1);
  row = (0.5 * frame.diameter - z) / frame.diameter * (image.height - 1);
}

}  // namespace

void draw_profile(RgbImage& image, const DrumFrame& frame, const SurfaceProfile& profile, std::uint8_t red,
                  std::uint8_t green, std::uint8_t blue) {
  for (std::size_t i = 0; i + 1 < profile.x.size(); ++i) {
    double c0, r0, c1, r1;
    to_pixel(image, frame, profile.x[i], profile.z[i], c0, r0);
    to_pixel(image, frame, profile.x[i + 1], profile.z[i + 1], c1, r1);
    const int steps = 1 + static_cast<int>(2.0 * std::max(std::abs(c1 - c0), std::abs(r1 - r0)));
    for (int s = 0; s <= steps; ++s) {
      const double t = static_cast<double>(s) / steps;
      const int c = static_cast<int>(std::lround(c0 + t * (c1 - c0))),
                r = static_cast<int>(std::lround(r0 + t * (r1 - r0)));
      for (int dr = -1; dr <= 1; ++dr)
        for (int dc = -1; dc <= 1; ++dc) paint(image, c + dc, r + dr, red, green, blue);
    }
  }
}

RgbImage draw_overlay(const GreyImage& photo, const DrumFrame& frame, const SurfaceProfile& profile) {
  RgbImage image = to_rgb(photo);
  const int samples = 8 * (image.width + image.height);
  for (int s = 0; s < samples; ++s) {
    const double angle = 2.0 * M_PI * s / samples;
    double c, r;
    to_pixel(image, frame, profile.compared_radius * std::cos(angle), profile.compared_radius * std::sin(angle), c, r);
    paint(image, static_cast<int>(std::lround(c)), static_cast<int>(std::lround(r)), 40, 90, 255);
  }
  draw_profile(image, frame, profile, 230, 20, 20);
  return image;
}

}  // namespace demfit::imaging
