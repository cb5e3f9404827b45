#pragma once
// Minimisation of a cheap (predicted) objective over a box: a deterministic global stage (NLopt
// DIRECT-L) followed by gradient-based polishing (NLopt LD_LBFGS, or LN_BOBYQA without gradient)
// from the best distinct points of the global stage.
#include "demfit/rbf_surrogate/bounds.hpp"

#include <cstdint>
#include <functional>

namespace demfit::rbf_surrogate {

// Must fill *gradient (same size as x) when it is non-null and use_gradient is true.
using Objective = std::function<double(const VectorXd& x, VectorXd* gradient /*may be null*/)>;

struct MinimizeOptions {
  int global_evaluations = 2000;  // DIRECT-L budget
  int local_starts = 5;           // polishing runs from the best distinct global points
  std::uint64_t seed = 1;
  bool use_gradient = true;     // false: LN_BOBYQA polishing, gradient never requested
  int local_evaluations = 200;  // per polishing run
};

struct MinimizeResult {
  VectorXd x;
  double value = 0.0;
  int evaluations = 0;
};

MinimizeResult minimize(const Objective& objective, const Box& box, const MinimizeOptions& options = {});

}  // namespace demfit::rbf_surrogate
