#pragma once
// Seeded Gaussian noise for synthetic "measured" curves (docs/spec.md 2.1 shipped data).
// Noise on y: N(0, (relative * max|y|)^2), independent per point. The generator is
// std::mt19937_64 with a Box-Muller transform written here, so the same seed gives the same
// numbers with any standard library (std::normal_distribution is implementation-defined).
#include <cstdint>
#include <vector>

namespace demfit::cases {

// Returns y + noise. relative >= 0 (0 returns y unchanged).
std::vector<double> add_relative_noise(const std::vector<double>& y, double relative, std::uint64_t seed);

}  // namespace demfit::cases
