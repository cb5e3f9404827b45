#pragma once
// Cheap screening of candidate effects at the base optimum: a score (Lagrange-multiplier) test.
// Each effect parameter is switched on slightly (one model evaluation per parameter); the change
// of the normalised residual, with the part the base variables can already absorb projected out,
// is regressed on the residual. Under "the effect is absent" the score statistic is chi-square
// with (effect parameters) degrees of freedom.
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "demfit/diagnose/effect.hpp"
#include "demfit/diagnose/least_squares.hpp"

namespace demfit::diagnose {

struct ScreeningScore {
  std::string effect;
  double score = 0.0;               // r' S (S'S)^-1 S' r with S the projected sensitivities
  double p_value = 1.0;             // chi-square upper tail, dof = effect parameters
  double fraction_explained = 0.0;  // score / |r|^2: share of the residual sum of squares
  // 1 − |S⊥|²/|S|² (Frobenius): the share of the effect's change of the curves that a change of the
  // free base variables reproduces; near 1 the effect looks like a change of the base variables.
  // A perturbed run's own trajectory noise lowers it (measured on the s = 4 drum: 0.17 / 0.001 for a
  // rolling friction the sliding friction absorbs), so on a noisy model a low share proves nothing.
  double absorbed_by_base = 0.0;
  // max over the effect's parameters of |S⊥_j Δ_j|², Δ_j from the off value to the far end of its
  // range (the side the screening stepped to): the chi-square gain the effect could bring at most,
  // in the linear picture, beyond what the base variables absorb. Below the naming criterion's
  // threshold, these data can neither show nor exclude the effect.
  double full_range_gain = 0.0;
  std::vector<double> start;  // linearised estimate of the effect parameters (clamped)
  bool evaluated = true;      // false if a perturbed evaluation failed
  // d residual / d effect parameter (model units) at the base optimum, one column per parameter,
  // before projection: seeds the Jacobian of the candidate's re-fit.
  Eigen::MatrixXd sensitivity;
};

// `base` is the base fit (normalised residual, parameters); `variables` the base fit variables.
// The base variables' sensitivities come from base.jacobian when it fits (no evaluation), else
// from one forward difference each. Returns one score per candidate, in candidate order. `step` = perturbation,
// fraction of each effect parameter's range, away from its off value.
std::vector<ScreeningScore> screen_candidates(const identify::Model& model, const FitResult& base,
                                              const std::vector<FitVariable>& variables,
                                              const std::vector<FitTarget>& targets,
                                              const std::vector<EffectCandidate>& candidates, double step,
                                              const FitOptions& options, int* evaluations = nullptr);

}  // namespace demfit::diagnose
