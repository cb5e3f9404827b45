// Seeded Gaussian noise (see synthetic_noise.hpp).
#include "demfit/cases/synthetic_noise.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>

namespace demfit::cases {

std::vector<double> add_relative_noise(const std::vector<double>& y, double relative, std::uint64_t seed) {
  if (!(relative >= 0.0)) throw std::runtime_error("--noise must be >= 0 (relative to max|y|)");
  double scale = 0.0;
  for (double v : y) scale = std::max(scale, std::fabs(v));
  const double sigma = relative * scale;
  std::mt19937_64 engine(seed);
  // Uniform in (0, 1]: 53 random bits, shifted so log() never sees 0.
  auto uniform = [&engine] { return (static_cast<double>(engine() >> 11) + 1.0) * 0x1.0p-53; };
  std::vector<double> out = y;
  for (std::size_t i = 0; i < out.size(); ++i) {
    const double u1 = uniform();
    const double u2 = uniform();
    const double normal = std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
    out[i] += sigma * normal;
  }
  return out;
}

}  // namespace demfit::cases
