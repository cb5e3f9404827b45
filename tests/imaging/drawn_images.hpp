#pragma once
// Test images drawn in memory: a square picture of a drum of diameter D with a known free surface
// z = surface(x) (drum frame, metres). Each pixel's grey level is the area fraction of the pixel
// below the surface (8 x 8 sub-samples), blended between an empty and a material grey level.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "demfit/imaging/image.hpp"
#include "demfit/imaging/surface.hpp"

namespace demfit::imaging::test {

// Test pictures are written with a plain stream: imaging itself writes no files.
inline void write_png(const std::filesystem::path& file, const RgbImage& image) {
  std::ofstream out(file, std::ios::binary);
  out << encode_png(image);
}

// Raw bytes to a file (an image file made by hand, or a damaged one).
inline void write_bytes(const std::filesystem::path& file, const std::string& bytes) {
  std::ofstream(file, std::ios::binary) << bytes;
}

struct DrawnDrum {
  int pixels = 406;
  double diameter = 0.084;  // [m]
  float material = 0.12f;   // grey level of the powder
  float empty = 0.92f;      // grey level of the empty drum
  double pixel_size() const { return diameter / (pixels - 1); }
};

inline GreyImage draw_surface(const DrawnDrum& drum, const std::function<double(double)>& surface) {
  GreyImage image;
  image.width = image.height = drum.pixels;
  image.value.resize(static_cast<std::size_t>(drum.pixels) * drum.pixels);
  const double h = drum.pixel_size();
  constexpr int kSub = 8;
  for (int row = 0; row < drum.pixels; ++row)
    for (int column = 0; column < drum.pixels; ++column) {
      const double xc = pixel_x(column, drum.pixels, drum.diameter), zc = pixel_z(row, drum.pixels, drum.diameter);
      int below = 0;
      for (int a = 0; a < kSub; ++a)
        for (int b = 0; b < kSub; ++b) {
          const double x = xc + ((a + 0.5) / kSub - 0.5) * h, z = zc + ((b + 0.5) / kSub - 0.5) * h;
          below += z < surface(x);
        }
      const float fraction = static_cast<float>(below) / (kSub * kSub);
      image.value[static_cast<std::size_t>(row) * drum.pixels + column] =
          drum.empty + (drum.material - drum.empty) * fraction;
    }
  return image;
}

// Sets the pixels whose centre lies at a distance in [inner, outer] from the axis to `grey`.
inline void paint_ring(GreyImage& image, double diameter, double inner, double outer, float grey) {
  for (int row = 0; row < image.height; ++row)
    for (int column = 0; column < image.width; ++column) {
      const double x = pixel_x(column, image.width, diameter), z = pixel_z(row, image.height, diameter);
      const double r = std::hypot(x, z);
      if (r >= inner && r <= outer) image.value[static_cast<std::size_t>(row) * image.width + column] = grey;
    }
}

// RMS of the profile's z against the analytic surface at the profile's abscissae [m].
inline double rms_against(const SurfaceProfile& profile, const std::function<double(double)>& surface) {
  double squares = 0.0;
  for (std::size_t i = 0; i < profile.x.size(); ++i) squares += std::pow(profile.z[i] - surface(profile.x[i]), 2);
  return std::sqrt(squares / static_cast<double>(profile.x.size()));
}

}  // namespace demfit::imaging::test
