#include "demfit/identify/analytic_model.hpp"

#include <cmath>
#include <stdexcept>

namespace demfit::identify {

AnalyticCurveModel::AnalyticCurveModel(int points) : points_(points) {
  if (points_ < 2) throw std::runtime_error("analytic model: points must be >= 2");
}

std::vector<ParameterDescriptor> AnalyticCurveModel::parameters() const {
  return unbounded_descriptors({"amplitude", "rate", "slope"});
}

std::vector<CurveDescriptor> AnalyticCurveModel::curves() const {
  return {{"response", "x_1", "y_1"}, {"loop", "x_1", "y_1"}};
}

ParameterSet AnalyticCurveModel::default_parameters() const {
  return {{"amplitude", 1.0}, {"rate", 3.0}, {"slope", 0.5}};
}

CurveSet AnalyticCurveModel::evaluate(const ParameterSet& parameters, const EvaluationContext&) const {
  ParameterSet p = default_parameters();
  for (const auto& [name, value] : parameters) {
    if (!p.count(name)) throw std::runtime_error("analytic model: unknown parameter '" + name + "'");
    if (!std::isfinite(value)) throw std::runtime_error("analytic model: parameter '" + name + "' is not finite");
    p[name] = value;
  }
  const double a = p["amplitude"], r = p["rate"], b = p["slope"];
  auto loading = [&](double x) { return a * (1.0 - std::exp(-r * x)) + b * x; };
  Curve response{"x_1", "y_1", {}, {}};
  Curve loop{"x_1", "y_1", {}, {}};
  for (int i = 0; i < points_; ++i) {
    const double x = static_cast<double>(i) / (points_ - 1);
    response.x.push_back(x);
    response.y.push_back(loading(x));
    loop.x.push_back(x);
    loop.y.push_back(loading(x));
  }
  const double x0 = 0.2 + 0.3 * b / (1.0 + b);
  const double peak = loading(1.0);
  for (int i = 1; i < points_; ++i) {
    const double x = 1.0 - (1.0 - x0) * i / (points_ - 1);
    const double u = (x - x0) / (1.0 - x0);
    loop.x.push_back(x);
    loop.y.push_back(peak * u * u);
  }
  return {{"response", response}, {"loop", loop}};
}

}  // namespace demfit::identify
