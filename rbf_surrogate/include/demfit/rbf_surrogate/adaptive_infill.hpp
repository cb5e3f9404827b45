#pragma once
// Adaptive infill beyond SRSM: stochastic-RBF candidate scoring (Regis & Shoemaker 2007).
// Candidates (Gaussian perturbations of the best point + uniform points in the region) are scored
// w·V + (1-w)·D, V = predicted value scaled to [0,1], D = 1 - distance-to-existing scaled to [0,1];
// the weight w cycles through {0.3, 0.5, 0.8, 0.95} with the point index (global search -> local).
#include "demfit/rbf_surrogate/rbf_network.hpp"

#include <cstdint>

namespace demfit::rbf_surrogate {

// scalar_objective_model: an RbfNetwork whose output 0 is the objective to minimise.
// existing: points already run (rows, unit coordinates). Returns `points` rows inside `region`,
// none closer than 1e-5 to existing points or each other when the region allows it.
MatrixXd adaptive_infill(const RbfNetwork& scalar_objective_model, const MatrixXd& existing, int points,
                         const Box& region, std::uint64_t seed, int iteration);

}  // namespace demfit::rbf_surrogate
