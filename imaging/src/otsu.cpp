// Otsu's threshold: the grey level that maximises the between-class variance of a two-class split
// (N. Otsu, IEEE Trans. SMC 9 (1979) 62-66), over the pixels inside the compared circle.
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "demfit/imaging/surface.hpp"

namespace demfit::imaging {
namespace {

constexpr int kBins = 256;

std::array<double, kBins> circle_histogram(const GreyImage& image, double margin) {
  std::array<double, kBins> histogram{};
  const int n = image.width;
  const double centre = 0.5 * (n - 1);
  const double radius = (1.0 - margin) * centre;  // in pixel units
  for (int row = 0; row < image.height; ++row)
    for (int column = 0; column < n; ++column) {
      const double dx = column - centre, dz = row - centre;
      if (dx * dx + dz * dz > radius * radius) continue;
      const double v = image.value[static_cast<std::size_t>(row) * n + column];
      const int bin = std::min(kBins - 1, std::max(0, static_cast<int>(std::floor(v * kBins))));
      histogram[bin] += 1.0;
    }
  return histogram;
}

}  // namespace

double otsu_threshold(const GreyImage& image, double margin) {
  const std::array<double, kBins> histogram = circle_histogram(image, margin);
  double total = 0.0, total_moment = 0.0;
  for (int k = 0; k < kBins; ++k) {
    total += histogram[k];
    total_moment += k * histogram[k];
  }
  // Between-class variance w0 w1 (mu0 - mu1)^2 for the split "bins <= k | bins > k".
  std::array<double, kBins> between{};
  double weight0 = 0.0, moment0 = 0.0, best = 0.0;
  for (int k = 0; k < kBins - 1; ++k) {
    weight0 += histogram[k];
    moment0 += k * histogram[k];
    const double weight1 = total - weight0;
    if (weight0 <= 0.0 || weight1 <= 0.0) continue;
    const double difference = moment0 / weight0 - (total_moment - moment0) / weight1;
    between[k] = weight0 * weight1 * difference * difference;
    best = std::max(best, between[k]);
  }
  const std::string name = image.source.empty() ? std::string("image") : "image '" + image.source + "'";
  if (best <= 0.0)
    throw std::runtime_error(name +
                             ": a single grey level inside the compared circle, so no material/empty split exists; "
                             "check that it is a drum photo (not all dark or all light)");
  // Empty bins between the two modes give a plateau of equal variance; its middle keeps the
  // threshold halfway between the modes (Otsu's first maximum would hug the lower mode).
  int first = -1, last = -1;
  for (int k = 0; k < kBins - 1; ++k)
    if (between[k] >= best * (1.0 - 1e-12)) {
      if (first < 0) first = k;
      last = k;
    }
  return 0.5 * ((first + 1) + (last + 1)) / kBins;
}

}  // namespace demfit::imaging
