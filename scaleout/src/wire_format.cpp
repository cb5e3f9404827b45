#include "demfit/scaleout/wire_format.hpp"

#include <nlohmann/json.hpp>

#include "demfit/identify/curve_json.hpp"

namespace demfit::scaleout {

using nlohmann::json;

std::string encode_parameters(const identify::ParameterSet& parameters) { return json(parameters).dump(); }

identify::ParameterSet decode_parameters(const std::string& text) {
  return json::parse(text).get<identify::ParameterSet>();
}

std::string encode_job(const identify::EvaluationJob& job) {
  return json{{"experiment", job.experiment}, {"parameters", job.parameters}}.dump();
}

identify::EvaluationJob decode_job(const std::string& text) {
  const json message = json::parse(text);
  return {message.at("experiment").get<std::size_t>(), message.at("parameters").get<identify::ParameterSet>()};
}

std::string encode_outcome(const identify::EvaluationOutcome& outcome) {
  return json{{"ok", outcome.ok},
              {"error", outcome.error},
              {"wall_seconds", outcome.wall_seconds},
              {"curves", identify::curves_to_json(outcome.curves)}}
      .dump();
}

identify::EvaluationOutcome decode_outcome(const std::string& text) {
  const json message = json::parse(text);
  identify::EvaluationOutcome outcome;
  outcome.ok = message.at("ok").get<bool>();
  outcome.error = message.at("error").get<std::string>();
  outcome.wall_seconds = message.at("wall_seconds").get<double>();
  outcome.curves = identify::curves_from_json(message.at("curves"));
  return outcome;
}

}  // namespace demfit::scaleout
