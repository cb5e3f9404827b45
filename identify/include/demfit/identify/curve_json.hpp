#pragma once
// The one Curve <-> JSON conversion, used by the study store, the case result
// cache and the MPI wire format. A curve is {"x_label": .., "y_label": .., "x": [..], "y": [..]}
// (units are part of the labels, as in the CSV header); a CurveSet is an object of curves by name.
// nlohmann-json writes doubles in the shortest form that reads back to the same bits, so a curve
// survives a round trip exactly.
#include <nlohmann/json.hpp>

#include "demfit/identify/model.hpp"

namespace demfit::identify {

nlohmann::json curve_to_json(const Curve& curve);
// Throws nlohmann::json::exception when a field is missing or has the wrong type.
Curve curve_from_json(const nlohmann::json& json);

nlohmann::json curves_to_json(const CurveSet& curves);
CurveSet curves_from_json(const nlohmann::json& json);

}  // namespace demfit::identify
