#pragma once
// Space-filling designs (docs/spec.md section 3; LS-OPT "space filling" point selection).
// Points are ROWS, in unit coordinates. Deterministic: std::mt19937_64 with our own uniform
// mapping (std distributions are implementation-defined).
#include "demfit/rbf_surrogate/bounds.hpp"

#include <cstdint>
#include <random>

namespace demfit::rbf_surrogate {

// Latin hypercube of `points` rows in `region`: every 1-D projection has exactly one point in each
// of the `points` equal strata (points at stratum centres), and column permutations are improved by
// pair swaps to maximise the minimum inter-point distance (Morris-Mitchell phi_p criterion, measured
// in region-normalised coordinates).
MatrixXd latin_hypercube_maximin(int points, int dims, std::uint64_t seed, const Box& region);

// Plain (random) Latin hypercube with stratum-centred points: the baseline for the maximin test.
MatrixXd latin_hypercube_random(int points, int dims, std::uint64_t seed, const Box& region);

// `points` new rows inside `region` maximising the minimum distance to every existing point and to
// each other (greedy maximin over a seeded candidate pool, then exchange improvement). Distances are
// measured in region-normalised coordinates so a narrow subregion is filled evenly in every direction.
MatrixXd space_filling_augment(const MatrixXd& existing, int points, const Box& region, std::uint64_t seed);

// Smallest pairwise Euclidean distance between rows (infinity for fewer than 2 rows).
double minimum_distance(const MatrixXd& points);

// Deterministic uniform numbers from std::mt19937_64 (the same on every platform).
double uniform01(std::mt19937_64& rng);                              // [0, 1), 53 random bits
double normal01(std::mt19937_64& rng);                               // standard normal (Box-Muller), reproducible
std::uint64_t uniform_index(std::mt19937_64& rng, std::uint64_t n);  // [0, n)

}  // namespace demfit::rbf_surrogate
