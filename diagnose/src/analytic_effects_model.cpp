// Analytic curve family with optional effect terms; see analytic_effects_model.hpp.
#include "demfit/diagnose/analytic_effects_model.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>

namespace demfit::diagnose {

AnalyticEffectsModel::AnalyticEffectsModel(int points) : points_(points) {
  if (points_ < 3) throw std::runtime_error("analytic effects model: points must be >= 3");
}

std::vector<identify::ParameterDescriptor> AnalyticEffectsModel::parameters() const {
  return identify::unbounded_descriptors(
      {"amplitude", "rate", "slope", "toe_shift", "stiffening_coefficient", "yield_drop", "ripple_amplitude"});
}

identify::ParameterSet AnalyticEffectsModel::default_parameters() const {
  return {{"amplitude", 1.0},
          {"rate", 3.0},
          {"slope", 0.5},
          {"toe_shift", 0.0},
          {"stiffening_coefficient", 0.0},
          {"yield_drop", 0.0},
          {"ripple_amplitude", 0.0}};
}

identify::CurveSet AnalyticEffectsModel::evaluate(const identify::ParameterSet& parameters,
                                                  const identify::EvaluationContext&) const {
  identify::ParameterSet p = default_parameters();
  for (const auto& [name, value] : parameters) {
    if (!p.count(name)) throw std::runtime_error("analytic effects model: unknown parameter '" + name + "'");
    if (!std::isfinite(value))
      throw std::runtime_error("analytic effects model: parameter '" + name + "' is not finite");
    p[name] = value;
  }
  const double a = p["amplitude"], r = p["rate"], b = p["slope"];
  const double shift = p["toe_shift"], c = p["stiffening_coefficient"], h = p["yield_drop"], e = p["ripple_amplitude"];
  identify::Curve curve{"x_1", "y_1", {}, {}};
  for (int i = 0; i < points_; ++i) {
    const double x = static_cast<double>(i) / (points_ - 1);
    const double xs = std::max(x - shift, 0.0);
    double y = a * (1.0 - std::exp(-r * xs)) + b * xs;
    y += c * x * x;
    y -= h * std::max(x - 0.7, 0.0) / 0.3;
    y += e * std::sin(4.0 * std::numbers::pi * x);
    curve.x.push_back(x);
    curve.y.push_back(y);
  }
  return {{"response", curve}};
}

identify::StudySpec analytic_effects_study(const identify::ParameterSet& truth, unsigned seed, double noise,
                                           int points) {
  const AnalyticEffectsModel model(points);
  identify::Curve data = model.evaluate(truth, {}).at("response");
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, noise);
  for (auto& y : data.y) y += normal(rng);
  identify::StudySpec spec;
  spec.name = "synthetic";
  spec.model_reference = "analytic";
  spec.variables = {{"amplitude", 0.5, 2.0, 1.2, false, 1.0},
                    {"rate", 1.0, 8.0, 4.0, false, 1.0},
                    {"slope", 0.0, 1.5, 0.3, false, 1.0}};
  identify::TargetSpec target;
  target.name = target.curve = "response";
  target.data = data;
  spec.targets = {target};
  return spec;
}

}  // namespace demfit::diagnose
