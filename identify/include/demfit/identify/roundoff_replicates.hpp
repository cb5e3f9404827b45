#pragma once
// Round-off replicates: the same parameters moved by a few 1e-7 of each variable's range. A DEM
// run is chaotic, so such a run is another trajectory of the same physics; the spread of a result
// over replicates is how sure one run of it can be. Used by the interval-end checks
// (interval_check.hpp: the spread of the best point's objective) and by `reproduce table3` (the
// spread of the surface error at the initial and the identified values).
#include <vector>

#include <Eigen/Dense>

#include "demfit/identify/model.hpp"
#include "demfit/identify/study_spec.hpp"

namespace demfit::identify {

inline constexpr double kReplicateNudge = 1e-7;  // unit coordinates per replicate

// Replicate r >= 0 of a point in unit coordinates: every coordinate moved by (r + 1) nudges,
// upwards unless that leaves [0, 1].
Eigen::VectorXd replicate_point(const Eigen::VectorXd& unit, int replicate);

// The same in model units for the study's variables (names and values of `values`; parameters
// that are not study variables are copied unchanged).
ParameterSet replicate_parameters(const StudySpec& spec, const ParameterSet& values, int replicate);

// Mean, sample standard deviation and range of replicated results (count >= 1; sd 0 for one).
struct ReplicateSpread {
  double mean = 0.0;
  double standard_deviation = 0.0;
  double lowest = 0.0;
  double highest = 0.0;
  int count = 0;
};
// Throws std::invalid_argument when `values` is empty or holds a value that is not finite.
ReplicateSpread replicate_spread(const std::vector<double>& values);

// Ratio of two replicated means with an approximate 95 % range: ±2 standard errors of the ratio by
// first-order error propagation (independent samples): se² = r² (s_a² / (n_a a²) + s_b² / (n_b b²)).
struct RatioOfMeans {
  double ratio = 0.0;
  double lower = 0.0;
  double upper = 0.0;
};
// Throws std::invalid_argument when the denominator's mean is not positive.
RatioOfMeans ratio_of_means(const ReplicateSpread& numerator, const ReplicateSpread& denominator);

}  // namespace demfit::identify
