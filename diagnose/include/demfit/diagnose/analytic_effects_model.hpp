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

}  // namespace demfit::diagnose
