#include "demfit/scaleout/wire_format.hpp"

#include <nlohmann/json.hpp>

namespace demfit::scaleout {

using nlohmann::json;

std::string encode_parameters(const identify::ParameterSet& parameters) {
  return json(parameters).dump();
}

identify::ParameterSet decode_parameters(const std::string& text) {
  return json::parse(text).get<identify::ParameterSet>();
}

std::string encode_outcome(const identify::EvaluationOutcome& outcome) {
  json curves = json::object();
  for (const auto& [name, curve] : outcome.curves) {
    curves[name] = {{"x_label", curve.x_label}, {"y_label", curve.y_label}, {"x", curve.x}, {"y", curve.y}};
  }
  return json{{"ok", outcome.ok}, {"error", outcome.error}, {"wall_seconds", outcome.wall_seconds},
              {"curves", curves}}
      .dump();
}

identify::EvaluationOutcome decode_outcome(const std::string& text) {
  const json message = json::parse(text);
  identify::EvaluationOutcome outcome;
  outcome.ok = message.at("ok").get<bool>();
  outcome.error = message.at("error").get<std::string>();
  outcome.wall_seconds = message.at("wall_seconds").get<double>();
  for (const auto& [name, curve] : message.at("curves").items()) {
    identify::Curve& decoded = outcome.curves[name];
    decoded.x_label = curve.at("x_label").get<std::string>();
    decoded.y_label = curve.at("y_label").get<std::string>();
    decoded.x = curve.at("x").get<std::vector<double>>();
    decoded.y = curve.at("y").get<std::vector<double>>();
  }
  return outcome;
}

}  // namespace demfit::scaleout
