#pragma once
// A re-fit start found by a global surrogate search instead of a local descent. A DEM model's
// chi-square is one trajectory's: where its run-to-run scatter is as deep as the valley the
// re-fit must find (a narrow cohesion optimum, docs/diagnose.md), a least-squares descent from
// any single start follows the noise. Here the space of base + effect variables is sampled by a
// maximin design and then by batches of expected-improvement points of a kriging model whose
// nugget is estimated (rbf_surrogate/strategy.hpp, the identify loop's own strategy), so the
// noise is averaged over a region; the start is the run point of lowest predicted mean of that
// model, not the luckiest run.
#include <cstdint>
#include <vector>

#include "demfit/diagnose/least_squares.hpp"

namespace demfit::diagnose {

struct SurrogateStart {
  std::vector<double> values;  // physical, FitVariable order
  double predicted_chi_square = 0.0;
  double run_chi_square = 0.0;  // of the one run at `values`
  // That run's residual (normalised, targets' order), so the point is judged without running it
  // again; empty when the point chosen is one of the known points (it was not run here).
  Eigen::VectorXd run_residual;
  int evaluations = 0;          // model evaluations the search spent (failed ones included)
};

// Searches `variables` (their bounds; their starts and `known_values`/`known_chi_squares`, points
// already run, are told to the model first) for `evaluations` model runs, `fit.jobs` at a time,
// minimising the chi-square of `targets`. Deterministic for `seed`. Throws std::runtime_error if
// fewer than 3 runs succeeded.
SurrogateStart surrogate_search_start(const identify::Model& model, const identify::ParameterSet& fixed,
                                      const std::vector<FitVariable>& variables, const std::vector<FitTarget>& targets,
                                      const FitOptions& fit, int evaluations, std::uint64_t seed,
                                      const std::vector<std::vector<double>>& known_values = {},
                                      const std::vector<double>& known_chi_squares = {});

}  // namespace demfit::diagnose
