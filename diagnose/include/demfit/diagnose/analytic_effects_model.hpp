#pragma once
// The analytic curve family of identify::AnalyticCurveModel with optional effect terms, each
// vanishing at its off value (0), for tests and demos of the diagnosis workflow:
//   base        y0(x) = a (1 - exp(-r x)) + b x                  (amplitude, rate, slope)
//   toe_shift   y0 evaluated at max(x - s, 0): a late start, s in x units  (toe_shift)
//   stiffening  + c x^2                                          (stiffening_coefficient)
//   yield_drop  - h max(x - 0.7, 0) / 0.3 : softening past x=0.7 (yield_drop)
//   ripple      + e sin(4 pi x): a non-physical artefact, not a candidate (ripple_amplitude)
// Curve "response", x = 0..1 in `points` steps (labels x_1, y_1, dimensionless).
#include "demfit/identify/model.hpp"
#include "demfit/identify/study_spec.hpp"

namespace demfit::diagnose {

class AnalyticEffectsModel final : public identify::Model {
 public:
  explicit AnalyticEffectsModel(int points = 41);
  std::vector<identify::ParameterDescriptor> parameters() const override;
  identify::ParameterSet default_parameters() const override;
  identify::CurveSet evaluate(const identify::ParameterSet& parameters,
                              const identify::EvaluationContext& context) const override;

 private:
  int points_;
};

// A synthetic study on this family for tests and benchmarks: the "response" curve at `truth` (a
// real experiment's data: the true curve) plus seeded white noise of standard deviation `noise`
// (y units); base variables amplitude [0.5, 2] from 1.2, rate [1, 8] from 4, slope [0, 1.5] from 0.3.
identify::StudySpec analytic_effects_study(const identify::ParameterSet& truth, unsigned seed, double noise,
                                           int points = 101);

}  // namespace demfit::diagnose
