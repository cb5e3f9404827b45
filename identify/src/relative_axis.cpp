#include "demfit/identify/relative_axis.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace demfit::identify {

Curve relative_axis_curve(const Curve& curve, const std::string& axis, const std::string& name) {
  double largest = 0.0;
  for (double y : curve.y) largest = std::max(largest, std::abs(y));
  std::size_t contact = curve.y.size();
  for (std::size_t i = 0; i < curve.y.size(); ++i)
    if (std::abs(curve.y[i]) > kContactFraction * largest) {
      contact = i;
      break;
    }
  if (largest == 0.0 || contact >= curve.x.size())
    throw std::runtime_error("curve '" + name + "': no first contact (y never leaves zero)");
  const double xc = curve.x[contact];
  Curve out;
  out.y_label = curve.y_label;
  const auto underscore = curve.x_label.rfind('_');
  if (axis == "from_contact") {
    out.x_label = underscore == std::string::npos
                      ? curve.x_label + "_change"
                      : curve.x_label.substr(0, underscore) + "_change" + curve.x_label.substr(underscore);
  } else if (axis == "strain") {
    if (xc == 0.0) throw std::runtime_error("curve '" + name + "': x is 0 at first contact; strain is undefined");
    out.x_label = "volumetric_strain_1";
  } else {
    throw std::runtime_error("curve '" + name + "': unknown axis '@" + axis + "'; use @from_contact or @strain");
  }
  for (std::size_t i = contact; i < curve.x.size(); ++i) {
    out.x.push_back(axis == "strain" ? (xc - curve.x[i]) / xc : xc - curve.x[i]);
    out.y.push_back(curve.y[i]);
  }
  return out;
}

RelativeAxisModel::RelativeAxisModel(std::unique_ptr<Model> base, std::set<std::string> requested)
    : base_(std::move(base)), requested_(std::move(requested)) {}

CurveSet RelativeAxisModel::evaluate(const ParameterSet& parameters, const EvaluationContext& context) const {
  CurveSet curves = base_->evaluate(parameters, context);
  for (const std::string& name : requested_) {
    const auto at = name.find('@');
    const auto base = curves.find(name.substr(0, at));
    if (at == std::string::npos || base == curves.end()) continue;  // the preflight names a missing curve
    curves[name] = relative_axis_curve(base->second, name.substr(at + 1), name);
  }
  return curves;
}

}  // namespace demfit::identify
