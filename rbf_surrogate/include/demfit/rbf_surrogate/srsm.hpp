#pragma once
// Successive response surface method domain reduction (Stander & Craig 2002; docs/spec.md section 3).
//   d = 2 Δx / r,  ĉ = sign(d_k d_{k-1}) sqrt|d_k d_{k-1}|,  γ = ½[γ_pan(1+ĉ) + γ_osc(1-ĉ)],
//   λ = η + |d|(γ - η),  r <- λ r   (all per variable), centred on the new optimum, kept inside bounds.
#include "demfit/rbf_surrogate/bounds.hpp"

namespace demfit::rbf_surrogate {

struct SrsmSettings {
  double gamma_pan = 1.0;
  double gamma_osc = 0.6;
  double eta = 0.6;
};

struct Subregion {
  VectorXd center, range;  // unit coordinates; range = full side lengths
  Box box() const;
  static Subregion from_box(const Box& box);
};

struct SrsmState {
  Subregion region;
  VectorXd previous_move;  // d_{k-1}; empty at start (first update uses ĉ = 0, see srsm.cpp)
};

// Starting state covering `region` (e.g. Box::unit(n) or a user's initial range).
SrsmState srsm_start(const Box& region);

SrsmState srsm_update(const SrsmState& state, const VectorXd& new_optimum, const SrsmSettings& settings,
                      const Box& bounds);

// Validates the settings (0 < eta <= 1, 0 < gamma_osc <= gamma_pan ... ) with a one-line
// std::invalid_argument naming the field.
void validate(const SrsmSettings& settings);

}  // namespace demfit::rbf_surrogate
