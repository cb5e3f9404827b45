#pragma once
// The level part of a fit's misfit, target by target: the mean of (simulated - data) in each
// target's own units. Why: a fit that lies above its data in one target and below it in another
// has a structure *between* targets that the residual tests inside each target do not name (they
// see a smooth misfit, not its sign pattern across targets). In a multi-experiment drum study this
// is the bed level that rises between speeds more in the model than in the photos
// (docs/granudrum.md, "Where the 45 rpm gap lies").
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "demfit/diagnose/least_squares.hpp"

namespace demfit::diagnose {

struct TargetLevel {
  std::string target;
  double mean = 0.0;             // [y units] mean of simulated - data over the target's points
  double mean_over_sigma = 0.0;  // mean / the target's noise level
  double level_share = 0.0;      // mean^2 / mean of the squared residual, in [0, 1]
};

// One target's residual in y units from its normalised segment: sigma x for a white target, L x
// for one whitened by the model's scatter (FitTarget::noise_factor = L).
Eigen::VectorXd raw_residual(const FitTarget& target, const Eigen::VectorXd& normalised);

// `residual`: a fit's normalised residual concatenated over `targets` (FitResult::residual): r/sigma
// for white targets, L^-1 r for whitened ones (FitTarget::noise_factor), so r is recovered as
// sigma x or L x. Throws std::invalid_argument when the lengths do not match.
std::vector<TargetLevel> target_levels(const std::vector<FitTarget>& targets, const Eigen::VectorXd& residual);

// One sentence when two targets' levels have opposite signs and the level is at least half of
// each one's squared residual (level_share >= kLevelShareToReport); empty otherwise.
inline constexpr double kLevelShareToReport = 0.5;
std::string opposite_levels_text(const std::vector<TargetLevel>& levels);

}  // namespace demfit::diagnose
