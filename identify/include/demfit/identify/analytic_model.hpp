#pragma once
// A cheap Model with known answers, for tests and demos (case "analytic" in the CLI).
//   parameters: amplitude a (default 1), rate r [1/x] (default 3), slope b (default 0.5)
//   curve "response":  y(x) = a (1 - exp(-r x)) + b x,  x = 0 .. 1 in `points` steps
//                      (labels x_1, y_1: dimensionless)
//   curve "loop":      loading along y(x) for x 0 -> 1, then unloading to x0 = 0.2 + 0.3 b/(1+b)
//                      along y(1) ((x - x0)/(1 - x0))^2 (a hysteresis loop, non-monotone in x,
//                      for the curve-mapping metric)
// evaluate() throws std::runtime_error for an unknown parameter name or a non-finite value.
#include "demfit/identify/model.hpp"

namespace demfit::identify {

class AnalyticCurveModel final : public Model {
 public:
  explicit AnalyticCurveModel(int points = 41);
  std::vector<ParameterDescriptor> parameters() const override;
  ParameterSet default_parameters() const override;
  std::vector<CurveDescriptor> curves() const override;
  CurveSet evaluate(const ParameterSet& parameters, const EvaluationContext& context) const override;

 private:
  int points_;
};

}  // namespace demfit::identify
