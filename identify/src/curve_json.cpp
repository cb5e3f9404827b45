// Curve <-> JSON (format in curve_json.hpp).
#include "demfit/identify/curve_json.hpp"

namespace demfit::identify {

nlohmann::json curve_to_json(const Curve& curve) {
  return {{"x_label", curve.x_label}, {"y_label", curve.y_label}, {"x", curve.x}, {"y", curve.y}};
}

Curve curve_from_json(const nlohmann::json& json) {
  return Curve{json.at("x_label").get<std::string>(), json.at("y_label").get<std::string>(),
               json.at("x").get<std::vector<double>>(), json.at("y").get<std::vector<double>>()};
}

nlohmann::json curves_to_json(const CurveSet& curves) {
  nlohmann::json json = nlohmann::json::object();
  for (const auto& [name, curve] : curves) json[name] = curve_to_json(curve);
  return json;
}

CurveSet curves_from_json(const nlohmann::json& json) {
  CurveSet curves;
  for (const auto& item : json.items()) curves[item.key()] = curve_from_json(item.value());
  return curves;
}

}  // namespace demfit::identify
